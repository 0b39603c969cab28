// The reduced `oitbench stress` set on every registered technique: each
// case runs in its own process with a timeout, and none may fail (crash,
// hang, garbage, an exact technique off without counted truncation, or an
// unexpected error). This process never opens a GL context itself, so the
// children fork from a clean state.
#include <gtest/gtest.h>

#include <limits>

#include "harness/app/stress.h"

namespace oit {
namespace {

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

INSTANTIATE_TEST_SUITE_P(EveryTechnique, Stress, testing::ValuesIn(builtin_techniques().ids()),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

TEST(StressJudge, OutputRangeIsTheTechniquesOwn) {
  TechniqueDescriptor compositing;  // output_max 1 by default
  const std::vector<float> weighted_sum = {0.2f, 4.7f, 1.0005f, 1.0f, -0.5f, 0.0f, 0.0f, 1.0f};
  EXPECT_EQ(values_outside_output_range(compositing, weighted_sum), 2u);  // 4.7 and -0.5; 1.0005 is rounding
  TechniqueDescriptor unbounded;
  unbounded.output_max = std::numeric_limits<double>::infinity();
  EXPECT_EQ(values_outside_output_range(unbounded, weighted_sum), 1u);  // only -0.5
  const std::vector<float> broken = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()};
  EXPECT_EQ(values_outside_output_range(unbounded, broken), 2u);  // never finiteness
}

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
