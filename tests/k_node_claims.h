#pragma once
// What the techniques that keep k nodes per pixel with ordered access
// (multi_layer_alpha_blending, adaptive_transparency) claim alike, as
// parameterized tests: a test file instantiates them for its technique,
//   using test::KNodeClaims;
//   INSTANTIATE_TEST_SUITE_P(Name, KNodeClaims, ::testing::Values(test::KNodeTechnique{id, counter}));
// Every run also checks that the spin-lock fallback lost no fragment.
#include <gtest/gtest.h>

#include <ostream>
#include <string>

#include "tests/approximate_oit_fixture.h"

namespace oit::test {

struct KNodeTechnique {
  std::string id;
  // What the technique counts when a list outgrows k (removals, merges).
  std::string compression_counter;
};
inline void PrintTo(const KNodeTechnique& technique, std::ostream* out) { *out << technique.id; }

class KNodeClaims : public ::testing::TestWithParam<KNodeTechnique> {
 protected:
  static constexpr int kSize = 32;
  const std::string& technique() const { return GetParam().id; }
};

// k = 8 on 8 quad layers: exact in any submission order, nothing compressed.
TEST_P(KNodeClaims, ExactWhenKCoversTheDepthComplexityInAnyOrder) {
  for (const char* order : {"original", "reversed", "shuffled:4"}) {
    const RunResult r = run_ordered(one_frame(technique(), {{"k", "8"}}, "quads", {{"layers", "8"}}, kSize, order));
    ASSERT_TRUE(r.error.has_value());
    EXPECT_LT(r.error->max_abs, 1e-5) << order;
    EXPECT_EQ(extra_counter(r, GetParam().compression_counter), 0.0) << order;
  }
}

TEST_P(KNodeClaims, ErrorFallsAsKGrows) {
  expect_falling(rmse_per_value(technique(), {}, "k", {"1", "2", "4", "8", "16"}, "random_quads", {}, kSize),
                 "k on random_quads (depth complexity up to 21)");
}

// Deterministic frame to frame (llvmpipe shades each pixel in primitive
// order), but the image moves with the submission order once k = 2
// compresses 16 layers, and stays put when k = 16 keeps them all.
TEST_P(KNodeClaims, CheckOrderShowsTheDependenceOnRasterisationOrder) {
  const OrderCheck compressed = order_check(technique(), {{"k", "2"}}, "quads", {{"layers", "16"}}, kSize);
  ASSERT_EQ(compressed.status, "ok") << compressed.message;
  EXPECT_EQ(compressed.repeat_difference, 0.0);
  EXPECT_GT(compressed.largest_difference, 0.01);
  const OrderCheck complete = order_check(technique(), {{"k", "16"}}, "quads", {{"layers", "16"}}, kSize);
  EXPECT_LT(complete.largest_difference, 1e-5);
}

}  // namespace oit::test
