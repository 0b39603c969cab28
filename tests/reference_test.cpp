// The exact reference against the closed form of the stacked quads, its
// overflow handling, and the harness's error against it.
#include <gtest/gtest.h>

#include "tests/gl_fixture.h"
#include "scenes/stacked_quads.h"

namespace oit {
namespace {

RawParams quad_params(const StackedQuadsParams& p) {
  return {{"layers", std::to_string(p.layers)}, {"alpha", std::to_string(p.alpha)}, {"seed", std::to_string(p.seed)}};
}

// Every pixel of `image` must equal `expected` bit for bit.
void expect_uniform_image(const Image& image, const glm::vec4& expected) {
  size_t mismatches = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 4; ++c)
        if (image.at(x, y, c) != expected[c]) ++mismatches;
  EXPECT_EQ(mismatches, 0u) << "first pixel " << image.at(0, 0, 0) << "," << image.at(0, 0, 1) << ","
                            << image.at(0, 0, 2) << "," << image.at(0, 0, 3) << " expected " << expected.r << ","
                            << expected.g << "," << expected.b << "," << expected.a;
}

TEST(Reference, EqualsClosedFormOnStackedQuadsExactly) {
  for (uint32_t seed : {1u, 7u}) {
    const StackedQuadsParams p{.layers = 32, .seed = seed, .alpha = 0.3f};
    // alpha is passed as text; read it back the way the scene parses it.
    StackedQuadsParams parsed = p;
    parsed.alpha = float(std::stod(std::to_string(p.alpha)));
    const RunResult r = test::render_once("reference", {}, "quads", quad_params(p), 64, 48);
    expect_uniform_image(r.image, stacked_quads_closed_form(parsed, glm::vec3(0.0f)));
  }
}

TEST(Reference, EqualsClosedFormOverAColouredBackground) {
  RunSpec spec = test::one_frame("reference", {}, "quads", {{"layers", "8"}, {"alpha", "0.5"}}, 16);
  spec.background = glm::vec3(0.25f, 0.5f, 1.0f);
  const RunResult r = test::harness().run(spec);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  StackedQuadsParams p{.layers = 8, .seed = 1, .alpha = 0.5f};
  expect_uniform_image(r.image, stacked_quads_closed_form(p, spec.background));
}

TEST(Reference, PoolOverflowIsDetectedGrownAndRetried) {
  // One node per pixel for 16 layers must overflow; the image must still be exact.
  const StackedQuadsParams p{.layers = 16, .seed = 3, .alpha = 0.3f};
  StackedQuadsParams parsed = p;
  parsed.alpha = float(std::stod(std::to_string(p.alpha)));
  const RunResult r = test::render_once("reference", {{"initial_nodes_per_pixel", "1"}}, "quads", quad_params(p), 32, 32);
  EXPECT_GE(r.counters.overflow_retries, 1u);
  EXPECT_EQ(r.counters.fragments_stored, 16u * 32u * 32u);
  EXPECT_EQ(r.counters.fragments_dropped, 0u);
  expect_uniform_image(r.image, stacked_quads_closed_form(parsed, glm::vec3(0.0f)));
  // With room for every fragment there is no retry.
  const RunResult roomy = test::render_once("reference", {{"initial_nodes_per_pixel", "16"}}, "quads",
                                            quad_params(p), 32, 32);
  EXPECT_EQ(roomy.counters.overflow_retries, 0u);
}

TEST(Reference, ListsLongerThanTheGpuResolveAreResolvedOnTheCpuExactly) {
  // 600 layers: beyond the GPU resolve's 512-entry array.
  const StackedQuadsParams p{.layers = 600, .seed = 5, .alpha = 0.3f};
  StackedQuadsParams parsed = p;
  parsed.alpha = float(std::stod(std::to_string(p.alpha)));
  const RunResult r = test::render_once("reference", {}, "quads", quad_params(p), 4, 4);
  expect_uniform_image(r.image, stacked_quads_closed_form(parsed, glm::vec3(0.0f)));
}

TEST(Reference, HarnessErrorOfTheReferenceIsZero) {
  const RunResult r = test::render_once("reference", {}, "quads", {{"layers", "8"}}, 32, 32);
  ASSERT_TRUE(r.error.has_value());
  EXPECT_EQ(r.error->max_abs, 0.0);
  EXPECT_EQ(r.scene_fragments, 8u * 32u * 32u);
  EXPECT_EQ(r.max_depth_complexity, 8u);
}

TEST(Unsorted, DiffersClearlyFromTheReferenceOnQuads) {
  const RunResult r = test::render_once("unsorted", {}, "quads", {{"layers", "32"}}, 64, 64);
  ASSERT_TRUE(r.error.has_value());
  // Submission order is random in depth, so the blend is visibly wrong.
  EXPECT_GT(r.error->max_abs, 0.02);
  EXPECT_GT(r.error->rmse, 0.01);
}

TEST(Unsorted, IsExactWhenLayersArriveBackToFront) {
  // A single layer has no order to get wrong: unsorted must equal the reference
  // up to float blending (the reference blends in double).
  const RunResult r = test::render_once("unsorted", {}, "quads", {{"layers", "1"}}, 16, 16);
  ASSERT_TRUE(r.error.has_value());
  EXPECT_LT(r.error->max_abs, 1e-6);
}

}  // namespace
}  // namespace oit
