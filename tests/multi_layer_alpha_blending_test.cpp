// Multi-layer alpha blending: exact when k >= the depth complexity (any
// order) and when the fragments arrive front to back (any k, every merge
// then composes in order); otherwise its image depends on the
// rasterisation order, which `oitbench check-order` shows. Every run also
// checks that the spin-lock fallback lost no fragment (README proof).
#include <sstream>

#include "tests/approximate_oit_fixture.h"
#include "tests/k_node_claims.h"
#include "tests/oitbench_process.h"

namespace oit {
namespace {

constexpr int kSize = 32;
const test::OneFrameOf spec_of{"multi_layer_alpha_blending", kSize};

// random_quads with order=front_to_back submits the quads sorted, nearest
// first: each new fragment is the farthest, and merging it into the last
// layer is exactly the over operator, for every k (here 1 and 2). With
// k = 1 back to front is exact too (each new fragment lies in front of the
// one merged layer); a random order is not.
TEST(MultiLayerAlphaBlending, ExactForSortedSubmission) {
  for (const char* k : {"1", "2"}) {
    const RunResult r = test::run_ordered(spec_of({{"k", k}}, "random_quads", {{"order", "front_to_back"}}));
    ASSERT_TRUE(r.error.has_value());
    EXPECT_LT(r.error->max_abs, 1e-5) << k;
    EXPECT_GT(r.max_depth_complexity, 4u);
    EXPECT_GT(test::extra_counter(r, "merges"), 0.0) << k;
  }
  const RunResult back_to_front =
      test::run_ordered(spec_of({{"k", "1"}}, "random_quads", {{"order", "back_to_front"}}));
  EXPECT_LT(back_to_front.error->max_abs, 1e-5);
  const RunResult random = test::run_ordered(spec_of({{"k", "1"}}, "random_quads", {{"order", "random"}}));
  EXPECT_GT(random.error->max_abs, 0.05);
}

TEST(MultiLayerAlphaBlending, FiniteAndBoundedOnSpheres) {
  const RunResult r = test::run_ordered(spec_of({}, "spheres", {}));
  ASSERT_TRUE(r.error.has_value());
  EXPECT_EQ(test::garbage_values(r.image), 0u);
  EXPECT_LT(r.error->max_abs, 0.05);
  // k layers of 20 bytes, count and lock words, two counter words.
  EXPECT_EQ(r.counters.bytes_allocated, uint64_t(kSize) * kSize * (4u * 20u + 8u) + 8u);
}

// The command itself: its row for the technique says approximate and a
// difference between orders well above float noise.
TEST(MultiLayerAlphaBlending, CheckOrderCommandPrintsTheMovement) {
  const test::Outcome out = test::run_oitbench(std::string(OIT_BINARY_DIR) + "/mlab_check_order",
                                               "check-order --technique multi_layer_alpha_blending --scene quads "
                                               "--scene-set layers=16 --size 16x16 --seeds 1");
  ASSERT_EQ(out.exit_code, 0) << out.output;
  std::istringstream lines(out.output);
  std::string line;
  bool found = false;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    std::string id, kind, verdict;
    double same = -1.0, other = -1.0;
    if (!(fields >> id >> kind >> verdict >> same >> other) || id != spec_of.technique) continue;
    found = true;
    EXPECT_EQ(kind, "approximate");
    EXPECT_EQ(same, 0.0) << line;
    EXPECT_GT(other, 0.01) << line;
  }
  EXPECT_TRUE(found) << out.output;
}

using test::KNodeClaims;
INSTANTIATE_TEST_SUITE_P(MultiLayerAlphaBlending, KNodeClaims,
                         ::testing::Values(test::KNodeTechnique{spec_of.technique, "merges"}));

}  // namespace
}  // namespace oit
