// Adaptive transparency: exact when the visibility function keeps every
// fragment (k >= the depth complexity), approximate and order-dependent
// once it compresses, more accurate as k grows. Every run also checks that
// the spin-lock fallback lost no fragment (README of
// multi_layer_alpha_blending).
#include "tests/approximate_oit_fixture.h"
#include "tests/k_node_claims.h"

namespace oit {
namespace {

constexpr int kSize = 32;
const test::OneFrameOf spec_of{"adaptive_transparency", kSize};

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

using test::KNodeClaims;
INSTANTIATE_TEST_SUITE_P(AdaptiveTransparency, KNodeClaims,
                         ::testing::Values(test::KNodeTechnique{spec_of.technique, "node_removals"}));

}  // namespace
}  // namespace oit
