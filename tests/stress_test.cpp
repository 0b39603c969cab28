// The reduced `oitbench stress` set on every registered technique: each
// case runs in its own process with a timeout, and none may fail (crash,
// hang, garbage, an exact technique off without counted truncation, or an
// unexpected error). This process never opens a GL context itself, so the
// children fork from a clean state.
#include <gtest/gtest.h>

#include "harness/app/stress.h"

namespace oit {
namespace {

std::vector<std::string> technique_ids() {
  std::vector<std::string> ids;
  for (const auto& t : builtin_techniques().all()) ids.push_back(t.id);
  return ids;
}

class Stress : public testing::TestWithParam<std::string> {};

TEST_P(Stress, ReducedSetPasses) {
  const TechniqueDescriptor& technique = builtin_techniques().get(GetParam());
  std::vector<StressCase> cases = stress_cases(false);
  for (auto& edge : parameter_edge_cases(technique)) cases.push_back(edge);
  size_t passed = 0;
  for (const auto& c : cases) {
    std::string device;
    const StressOutcome o = run_stress_case(CommonOptions{}, technique, c, 120.0, device);
    EXPECT_NE(o.verdict, Verdict::fail) << technique.id << " / " << c.name << " [" << o.status << "] " << o.note
                                        << "\n  expected: " << c.expectation;
    passed += o.verdict == Verdict::pass;
  }
  // Most cases apply to every technique; a suite of skips proves nothing.
  EXPECT_GE(passed, cases.size() / 2) << technique.id;
}

INSTANTIATE_TEST_SUITE_P(EveryTechnique, Stress, testing::ValuesIn(technique_ids()),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

TEST(StressCases, ReducedIsASubsetOfFullAndCoversEveryKind) {
  const auto reduced = stress_cases(false), full = stress_cases(true);
  EXPECT_LT(reduced.size(), full.size());
  for (const char* kind : {"gap_ndc", "gap_eye", "coplanar", "alpha_opaque", "alpha_1e-4", "alpha_mixed", "layers_",
                           "size_1x1", "size_333x177", "zero_area", "nan_vertex", "empty_scene", "single_object"}) {
    bool found = false;
    for (const auto& c : reduced) found = found || c.name.find(kind) != std::string::npos;
    EXPECT_TRUE(found) << kind;
  }
}

}  // namespace
}  // namespace oit
