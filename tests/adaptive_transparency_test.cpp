// Adaptive transparency: exact when the visibility function keeps every
// fragment (k >= the depth complexity), approximate and order-dependent
// once it compresses, more accurate as k grows. Every run also checks that
// the spin-lock fallback lost no fragment (README of
// multi_layer_alpha_blending).
#include "tests/approximate_oit_fixture.h"

namespace oit {
namespace {

constexpr int kSize = 32;
const char* const kTechnique = "adaptive_transparency";
const test::OneFrameOf spec_of{kTechnique, kSize};

TEST(AdaptiveTransparency, ExactWhenKCoversTheDepthComplexityInAnyOrder) {
  for (const char* order : {"original", "reversed", "shuffled:4"}) {
    const RunResult r = test::run_ordered(spec_of({{"k", "8"}}, "quads", {{"layers", "8"}}, order));
    ASSERT_TRUE(r.error.has_value());
    EXPECT_LT(r.error->max_abs, 1e-5) << order;
    EXPECT_EQ(test::extra_counter(r, "node_removals"), 0.0) << order;
  }
}

TEST(AdaptiveTransparency, ErrorFallsAsKGrows) {
  test::expect_falling(
      test::rmse_per_value(kTechnique, {}, "k", {"1", "2", "4", "8", "16"}, "random_quads", {}, kSize),
      "k on random_quads (depth complexity up to 21)");
}

TEST(AdaptiveTransparency, FiniteAndBoundedOnQuadsAndSpheres) {
  const RunResult quads = test::run_ordered(spec_of({{"k", "2"}}, "quads", {{"layers", "32"}}));
  ASSERT_TRUE(quads.error.has_value());
  EXPECT_EQ(test::garbage_values(quads.image), 0u);
  EXPECT_LT(quads.error->max_abs, 0.2);
  // 32 fragments per pixel into 2 nodes: each fragment after the second
  // removes one node.
  EXPECT_EQ(test::extra_counter(quads, "node_removals"), double(30 * kSize * kSize));
  const RunResult spheres = test::run_ordered(spec_of({}, "spheres", {}));
  ASSERT_TRUE(spheres.error.has_value());
  EXPECT_EQ(test::garbage_values(spheres.image), 0u);
  EXPECT_LT(spheres.error->max_abs, 0.1);
  // k + 1 nodes of 8 bytes, count and lock words, RGBA32F accumulation, two counter words.
  EXPECT_EQ(spheres.counters.bytes_allocated, uint64_t(kSize) * kSize * (5u * 8u + 24u) + 8u);
}

TEST(AdaptiveTransparency, CheckOrderShowsTheDependenceOnRasterisationOrder) {
  const OrderCheck compressed = test::order_check(kTechnique, {{"k", "2"}}, "quads", {{"layers", "16"}}, kSize);
  ASSERT_EQ(compressed.status, "ok") << compressed.message;
  EXPECT_EQ(compressed.repeat_difference, 0.0);
  EXPECT_GT(compressed.largest_difference, 0.01);
  const OrderCheck complete = test::order_check(kTechnique, {{"k", "16"}}, "quads", {{"layers", "16"}}, kSize);
  EXPECT_LT(complete.largest_difference, 1e-5);
}

}  // namespace
}  // namespace oit
