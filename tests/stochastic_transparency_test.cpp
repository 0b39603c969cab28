// Stochastic transparency: exact for one layer (the alpha correction makes
// the coverage exact), noisy but bounded on many, the noise falling with
// the effective sample count (samples x passes), seeded and deterministic,
// and a sample count the device lacks is a skipped run that says so.
#include <map>

#include "tests/approximate_oit_fixture.h"

namespace oit::test {
namespace {

constexpr int kSize = 32;
const OneFrameOf spec_of{"stochastic_transparency", kSize};

// One fragment: every sample estimate of its transmittance is 1 (nothing
// lies in front), and compose writes (a c / a) * (1 - (1 - a)) = c a.
TEST(StochasticTransparency, SingleLayerIsExactThroughTheAlphaCorrection) {
  const RunResult r = run_ok(spec_of({}, "quads", {{"layers", "1"}}));
  ASSERT_TRUE(r.error.has_value());
  EXPECT_LT(r.error->max_abs, 1e-6);
}

// The estimate is unbiased with variance ~ 1 / samples: quadrupling the
// effective samples should roughly halve the RMSE; asserted: it falls.
TEST(StochasticTransparency, ErrorFallsWithMoreEffectiveSamples) {
  const std::vector<double> errors = test::rmse_per_value("stochastic_transparency", {{"samples", "4"}}, "passes",
                                                          {"1", "4", "16"}, "quads", {{"layers", "8"}}, kSize);
  test::expect_falling(errors, "passes at 4 samples");
  EXPECT_LT(errors[2], 0.6 * errors[0]);
}

// 4, 8 and 16 samples: each runs where GL_MAX_SAMPLES and
// GL_MAX_DEPTH_TEXTURE_SAMPLES allow it, and is otherwise a skipped row
// naming the count and the device's limits. Where 16 runs, it beats 4.
TEST(StochasticTransparency, SampleCountsTheDeviceLacksAreSkippedRowsThatSaySo) {
  test::gl_context();
  GLint max_samples = 0, max_depth_samples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  glGetIntegerv(GL_MAX_DEPTH_TEXTURE_SAMPLES, &max_depth_samples);
  std::map<int, double> rmse;
  for (int samples : {4, 8, 16}) {
    const RunResult r =
        test::harness().run(spec_of({{"samples", std::to_string(samples)}}, "quads", {{"layers", "8"}}));
    if (samples <= max_samples && samples <= max_depth_samples) {
      ASSERT_EQ(r.status, RunStatus::ok) << samples << ": " << r.message;
      EXPECT_EQ(test::extra_counter(r, "effective_samples"), double(samples));
      EXPECT_EQ(r.counters.bytes_allocated, uint64_t(kSize) * kSize * (20u * samples + 4u));
      rmse[samples] = r.error->rmse;
    } else {
      EXPECT_EQ(r.status, RunStatus::skipped) << samples;
      EXPECT_NE(r.message.find("samples=" + std::to_string(samples)), std::string::npos) << r.message;
      EXPECT_NE(r.message.find("GL_MAX_SAMPLES " + std::to_string(max_samples)), std::string::npos) << r.message;
    }
  }
  ASSERT_TRUE(rmse.count(4)) << "every GL 4.5 device has 4 samples";
  if (rmse.count(16)) {
    EXPECT_LT(rmse[16], rmse[4]);
  }
}

TEST(StochasticTransparency, SeededDeterministicAndOrderIndependent) {
  const RunResult first = run_ok(spec_of({{"seed", "7"}}, "quads", {{"layers", "8"}}));
  const RunResult again = run_ok(spec_of({{"seed", "7"}}, "quads", {{"layers", "8"}}));
  const RunResult other_seed = run_ok(spec_of({{"seed", "8"}}, "quads", {{"layers", "8"}}));
  // The masks hash the stable triangle id, not the arrival order.
  const RunResult shuffled = run_ok(spec_of({{"seed", "7"}}, "quads", {{"layers", "8"}}, "shuffled:2"));
  EXPECT_EQ(max_abs_difference(first.image, again.image), 0.0);
  EXPECT_GT(max_abs_difference(first.image, other_seed.image), 1e-3);
  EXPECT_LT(max_abs_difference(first.image, shuffled.image), 1e-5);
}

TEST(StochasticTransparency, FiniteAndBoundedOnQuadsAndSpheres) {
  const RunResult quads = run_ok(spec_of({{"passes", "2"}}, "quads", {{"layers", "32"}}));
  ASSERT_TRUE(quads.error.has_value());
  EXPECT_EQ(garbage_values(quads.image), 0u);
  EXPECT_LT(quads.error->max_abs, 0.3);
  EXPECT_EQ(quads.counters.passes, 5u);  // 2 x (depth, accumulation) + total transmittance
  const RunResult spheres = run_ok(spec_of({}, "spheres", {}));
  ASSERT_TRUE(spheres.error.has_value());
  EXPECT_EQ(garbage_values(spheres.image), 0u);
  EXPECT_LT(spheres.error->max_abs, 0.3);
}

}  // namespace
}  // namespace oit::test
