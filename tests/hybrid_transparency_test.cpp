// Hybrid transparency: the k nearest fragments composed exactly (up to the
// core's RGBA8 colours), the rest as one weighted-average tail; the error
// falls as k grows and vanishes, up to that quantisation, at k >= the
// depth complexity.
#include "tests/approximate_oit_fixture.h"

namespace oit {
namespace {

using test::garbage_values;
using test::one_frame;
using test::run_ok;

constexpr int kSize = 32;

// Quantisation bound for k >= depth complexity. The composite
// C = sum_i c_i a_i T_i (T_i = prod_(j<i) (1 - a_j)) has |dC/dc_i| = a_i T_i
// and |dC/da_i| <= T_i (c_i and the colour behind, over 1 - a_i, both lie
// in [0, 1]), so RGBA8 rounding (at most 1/510 per value) moves it by at
// most (1/510) sum_i T_i (1 + a_i). Quads: a = 0.3, sum_i 0.7^i < 1/0.3:
// 1.3 / 0.3 / 510 = 8.5e-3. The alpha channel 1 - prod(1 - a_i) moves by at
// most (1/510) sum_i T_i, less.
constexpr double kRgba8Bound = 8.5e-3;

TEST(HybridTransparency, ExactUpToTheCoreColoursWhenKCoversTheDepthComplexity) {
  const RunResult r = run_ok(one_frame("hybrid_transparency", {{"k", "8"}}, "quads", {{"layers", "8"}}, kSize));
  ASSERT_TRUE(r.error.has_value());
  EXPECT_LT(r.error->max_abs, kRgba8Bound);
  EXPECT_EQ(r.counters.fragments_stored, uint64_t(8 * kSize * kSize));
  EXPECT_EQ(r.counters.fragments_dropped, 0u);
  EXPECT_EQ(test::extra_counter(r, "tied_to_tail"), 0.0);
  // 8 slots of 8 bytes + RGBA32F tail sum + R32F tail count per pixel, 8 counter bytes.
  EXPECT_EQ(r.counters.bytes_allocated, uint64_t(kSize) * kSize * (8u * 8u + 20u) + 8u);
}

TEST(HybridTransparency, ErrorFallsAsTheCoreGrows) {
  test::expect_falling(test::rmse_per_value("hybrid_transparency", {}, "k", {"1", "2", "4", "8", "16"},
                                            "random_quads", {}, kSize),
                       "k on random_quads (depth complexity up to 21)");
}

TEST(HybridTransparency, FiniteAndBoundedOnQuadsAndSpheres) {
  for (const char* k : {"1", "4"}) {
    const RunResult quads = run_ok(one_frame("hybrid_transparency", {{"k", k}}, "quads", {{"layers", "32"}}, kSize));
    ASSERT_TRUE(quads.error.has_value());
    EXPECT_EQ(garbage_values(quads.image), 0u) << k;
    EXPECT_LT(quads.error->max_abs, 0.2) << k;
    EXPECT_EQ(quads.counters.fragments_stored, uint64_t(std::stoi(k)) * kSize * kSize) << k;
    const RunResult spheres = run_ok(one_frame("hybrid_transparency", {{"k", k}}, "spheres", {}, kSize));
    ASSERT_TRUE(spheres.error.has_value());
    EXPECT_EQ(garbage_values(spheres.image), 0u) << k;
    EXPECT_LT(spheres.error->max_abs, 0.1) << k;
  }
}

// Within the core and in the tail's sums nothing depends on the order the
// fragments arrive in (distinct depths); only float summation order moves.
TEST(HybridTransparency, IsIndependentOfSubmissionOrderOnDistinctDepths) {
  const auto spec = [](const std::string& order) {
    return one_frame("hybrid_transparency", {{"k", "4"}}, "quads", {{"layers", "16"}}, kSize, order);
  };
  EXPECT_LT(test::max_abs_difference(run_ok(spec("original")).image, run_ok(spec("shuffled:5")).image), 1e-5);
}

}  // namespace
}  // namespace oit
