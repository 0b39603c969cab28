// Moment-based OIT: exact for one layer (the composite renormalises the
// single fragment to its true opacity), finite and bounded on many layers
// and on lit meshes, more accurate with more moments, and independent of
// the submission order (additive blending only).
#include "tests/approximate_oit_fixture.h"

namespace oit::test {
namespace {

constexpr int kSize = 32;
const OneFrameOf spec_of{"moment_oit", kSize};
const std::vector<std::string> kConfigurations = {"power4", "power6", "power8", "trig2", "trig3", "trig4"};

// One fragment per pixel: b0 = A = -ln(1 - a), and compose writes
// (T a c / T a) * (1 - e^-A) = c a whatever transmittance T was
// reconstructed. Float storage: only float rounding of exp/log (< 1e-6).
// Half storage: A = 0.357 rounded to half (relative 2^-11) moves
// 1 - e^-A by e^-A A 2^-11 = 1.2e-4, and rgb/a of RGBA16F values each
// rounded by 2^-11 moves the average colour (<= 0.9) by 2 * 0.9 * 2^-11 =
// 8.8e-4, times the coverage 0.3: 2.6e-4; together below 4e-4.
TEST(MomentOit, SingleLayerEqualsOverCompositingUpToStoragePrecision) {
  test::expect_single_layer_within_storage_precision(spec_of, "moments", kConfigurations, 1e-6, 4e-4);
}

// 32 layers of strongly different colours and the lit spheres: every
// configuration stays finite, inside [0, 1], and within a stated bound of
// the exact image (weighted_blended's eq10 reaches 0.08 on these quads).
TEST(MomentOit, FiniteAndBoundedOnQuadsAndSpheres) {
  for (const std::string& moments : kConfigurations) {
    for (const char* precision : {"float", "half"}) {
      const RawParams params = {{"moments", moments}, {"precision", precision}};
      const RunResult quads = run_ok(spec_of(params, "quads", {{"layers", "32"}}));
      ASSERT_TRUE(quads.error.has_value());
      EXPECT_EQ(garbage_values(quads.image), 0u) << moments << " " << precision;
      EXPECT_LT(quads.error->max_abs, 0.15) << moments << " " << precision;
      const RunResult spheres = run_ok(spec_of(params, "spheres", {}));
      ASSERT_TRUE(spheres.error.has_value());
      EXPECT_EQ(garbage_values(spheres.image), 0u) << moments << " " << precision;
      EXPECT_LT(spheres.error->max_abs, 0.15) << moments << " " << precision;
    }
  }
}

// The paper's convergence: more moments describe the absorbance over depth
// better, so the error falls from 4 to 6 to 8 power moments and from 2 to
// 3 to 4 trigonometric ones (RMSE over the image: 8 stacked quads, and
// random_quads, whose pixels hold from 0 to 21 fragments).
TEST(MomentOit, ErrorFallsWithMoreMoments) {
  for (const auto& family : {std::vector<std::string>{"power4", "power6", "power8"},
                             std::vector<std::string>{"trig2", "trig3", "trig4"}}) {
    test::expect_falling(
        test::rmse_per_value("moment_oit", {}, "moments", family, "quads", {{"layers", "8"}}, kSize), family[0]);
    test::expect_falling(test::rmse_per_value("moment_oit", {}, "moments", family, "random_quads", {}, kSize),
                         family[0] + " on random_quads");
  }
}

TEST(MomentOit, IsIndependentOfSubmissionOrder) {
  for (const char* moments : {"power6", "trig3"}) {
    const RunResult original = run_ok(spec_of({{"moments", moments}}, "quads", {{"layers", "16"}}));
    const RunResult shuffled = run_ok(spec_of({{"moments", moments}}, "quads", {{"layers", "16"}}, "shuffled:3"));
    EXPECT_LT(max_abs_difference(original.image, shuffled.image), 1e-5) << moments;
  }
}

// The overestimation moves the reconstruction from the lower bound (0) to
// the upper bound (1) of the absorbance in front: each fragment is
// attenuated more, and the counters report the configuration's bias.
TEST(MomentOit, OverestimationAndBiasAreApplied) {
  const RunResult lower = run_ok(spec_of({{"overestimation", "0"}}, "quads", {{"layers", "8"}}));
  const RunResult upper = run_ok(spec_of({{"overestimation", "1"}}, "quads", {{"layers", "8"}}));
  EXPECT_GT(max_abs_difference(lower.image, upper.image), 1e-3);
  const RunResult power8 =
      run_ok(spec_of({{"moments", "power8"}, {"moment_bias_scale", "2"}}, "quads", {{"layers", "2"}}));
  EXPECT_NEAR(test::extra_counter(power8, "moment_bias"), 1e-4, 1e-12);
  EXPECT_EQ(power8.counters.passes, 2u);
  // b0 + 8 moments + RGBA accumulation, 32-bit.
  EXPECT_EQ(power8.counters.bytes_allocated, uint64_t(kSize) * kSize * 4u * (1u + 8u + 4u));
}

TEST(MomentOit, RejectsABiasThatDiscardsTheMoments) {
  const RunResult r = test::harness().run(spec_of(
      {{"moments", "power8"}, {"precision", "half"}, {"moment_bias_scale", "1000"}}, "quads", {{"layers", "2"}}));
  EXPECT_EQ(r.status, RunStatus::error);
  EXPECT_NE(r.message.find("moment_bias_scale=1000"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace oit::test
