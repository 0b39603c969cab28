// Weighted blended OIT: exact for a single layer (up to the storage
// precision, bound derived below), approximate but finite on many layers,
// and independent of the submission order, for every weight function.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/approximate_oit_fixture.h"

namespace oit {
namespace {

constexpr int kSize = 32;
const std::vector<std::string> kWeights = {"eq7", "eq8", "eq9", "eq10"};

const test::OneFrameOf spec_of{"weighted_blended", kSize};
using test::run_ok;

using test::max_abs_difference;

// One fragment of straight colour c and opacity a per pixel (quads scene:
// c in [0.1, 0.9], a = 0.3, black background); the exact answer is c*a.
// WBOIT stores A = (w a c, w a) and R = 1 - a, composes c' (1 - R') with
// c' = A'.rgb / A'.a. Rounding each stored value to a format with unit
// roundoff u (half: 2^-11, float: 2^-24) gives |c' - c| <= c * 2u / (1 - u),
// and |R' - R| <= half an ulp of 0.7 = u / 2 (0.7 lies in [0.5, 1)), so
//   |c'(1 - R') - c a| <= c (2u/(1-u)) (a + u/2) + c u/2.
// Half: 0.9 * (9.77e-4 * 0.30025 + 2.44e-4) = 4.84e-4; alpha: u/2 = 2.44e-4.
// Float: 0.9 * (1.19e-7 * 0.3 + 2.98e-8) = 5.9e-8, plus the float rounding of
// the compose arithmetic itself (a few ulps of values <= 1): below 1e-6.
TEST(WeightedBlended, SingleLayerEqualsOverCompositingUpToStoragePrecision) {
  test::expect_single_layer_within_storage_precision(spec_of, "weight", kWeights, 1e-6, 4.9e-4);
}

TEST(WeightedBlended, ApproximateButFiniteOnThirtyTwoLayers) {
  for (const std::string& weight : kWeights) {
    const RunResult r = run_ok(spec_of({{"weight", weight}}, "quads", {{"layers", "32"}}));
    ASSERT_TRUE(r.error.has_value());
    EXPECT_TRUE(std::isfinite(r.error->max_abs)) << weight;
    EXPECT_TRUE(std::isfinite(r.error->rmse)) << weight;
    // A weighted average is not the sorted composite of 32 distinct colours.
    EXPECT_GT(r.error->max_abs, 1e-3) << weight;
    EXPECT_EQ(r.counters.fragments_stored, 0u);
    EXPECT_EQ(r.counters.fragments_dropped, 0u);
    EXPECT_EQ(r.counters.passes, 1u);
    EXPECT_EQ(r.counters.bytes_allocated, uint64_t(kSize) * kSize * (16u + 4u));
  }
  const RunResult half = run_ok(spec_of({{"precision", "half"}}, "quads", {{"layers", "32"}}));
  ASSERT_TRUE(half.error.has_value());
  EXPECT_TRUE(std::isfinite(half.error->max_abs));
  EXPECT_EQ(half.counters.bytes_allocated, uint64_t(kSize) * kSize * (8u + 2u));
}

TEST(WeightedBlended, RunsOnSpheres) {
  const RunResult r = run_ok(spec_of({}, "spheres", {}));
  ASSERT_TRUE(r.error.has_value());
  EXPECT_TRUE(std::isfinite(r.error->max_abs));
  EXPECT_GT(r.error->max_abs, 0.0);
  EXPECT_LT(r.error->max_abs, 0.5);
}

TEST(WeightedBlended, IsIndependentOfSubmissionOrder) {
  // Sums and products in RGBA32F/R32F commute up to float rounding.
  for (const std::string& weight : kWeights) {
    const RunResult original = run_ok(spec_of({{"weight", weight}}, "quads", {{"layers", "32"}}));
    const RunResult shuffled = run_ok(spec_of({{"weight", weight}}, "quads", {{"layers", "32"}}, "shuffled:7"));
    EXPECT_LT(max_abs_difference(original.image, shuffled.image), 1e-5) << weight;
  }
  const RunResult original = run_ok(spec_of({}, "spheres", {}));
  const RunResult reversed = run_ok(spec_of({}, "spheres", {}, "reversed"));
  EXPECT_LT(max_abs_difference(original.image, reversed.image), 1e-5);
}

TEST(WeightedBlended, RejectsAnUnknownWeight) {
  const RunResult r = test::harness().run(spec_of({{"weight", "eq6"}}, "quads", {{"layers", "2"}}));
  EXPECT_EQ(r.status, RunStatus::error);
  EXPECT_NE(r.message.find("'weight'"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace oit
