// The harness's scene rectangle (harness/toolkit/scene_rect.h, render_frame): the
// projection of the bounding box, and that scissoring every technique to it
// changes no image, also when the rectangle moves from frame to frame (a
// technique's per-pixel state outside the old rectangle must not leak in).
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

#include "harness/app/sweep.h"
#include "harness/run/results_csv.h"
#include "tests/gl_fixture.h"
#include "scenes/scene.h"
#include "scenes/scene_library.h"

namespace oit {
namespace {

const BoundingBox kUnitBox{glm::vec3(-1.0f), glm::vec3(1.0f), false};

glm::mat4 perspective_from(float eye_z, float znear = 0.1f) {
  return glm::perspective(glm::radians(45.0f), 1.0f, znear, 100.0f) *
         glm::lookAt(glm::vec3(0.0f, 0.0f, eye_z), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
}

TEST(SceneRect, BoxInFrontProjectsToItsNearFaceWidenedByOnePixel) {
  // The near face (z = 1) is 9 from the eye: it spans +-1 / (9 tan 22.5deg)
  // = +-0.26826 in NDC, i.e. pixels 23.42 .. 40.58 of 64; floor - 1 = 22,
  // ceil + 1 = 42.
  EXPECT_EQ(projected_scene_rect(kUnitBox, perspective_from(10.0f), 64, 64), (ScreenRect{22, 22, 20, 20}));
  // Wider than tall: x scales with the width only.
  const glm::mat4 wide = glm::perspective(glm::radians(45.0f), 2.0f, 0.1f, 100.0f) *
                         glm::lookAt(glm::vec3(0, 0, 10), glm::vec3(0), glm::vec3(0, 1, 0));
  EXPECT_EQ(projected_scene_rect(kUnitBox, wide, 128, 64), (ScreenRect{54, 22, 20, 20}));
}

TEST(SceneRect, OrthographicBoxMapsLinearly) {
  // ymag 4: the unit box covers the middle quarter of each axis (24 .. 40 of 64).
  const glm::mat4 ortho = glm::ortho(-4.0f, 4.0f, -4.0f, 4.0f, 0.5f, 20.0f) *
                          glm::lookAt(glm::vec3(0, 0, 10), glm::vec3(0), glm::vec3(0, 1, 0));
  EXPECT_EQ(projected_scene_rect(kUnitBox, ortho, 64, 64), (ScreenRect{23, 23, 18, 18}));
}

TEST(SceneRect, BoxReachingBehindTheNearPlaneOrTheEyeIsTheFullImage) {
  const ScreenRect full{0, 0, 64, 48};
  EXPECT_EQ(projected_scene_rect(kUnitBox, perspective_from(0.5f), 64, 48), full);        // eye inside the box
  EXPECT_EQ(projected_scene_rect(kUnitBox, perspective_from(1.05f, 0.1f), 64, 48), full);  // near plane cuts it
  // Entirely behind the eye: nothing is drawn, but the rectangle stays conservative.
  const glm::mat4 away = glm::perspective(glm::radians(45.0f), 1.0f, 0.1f, 100.0f) *
                         glm::lookAt(glm::vec3(0, 0, 10), glm::vec3(0, 0, 20), glm::vec3(0, 1, 0));
  EXPECT_EQ(projected_scene_rect(kUnitBox, away, 64, 48), full);
  const BoundingBox unbounded{glm::vec3(-INFINITY), glm::vec3(INFINITY), false};
  EXPECT_EQ(projected_scene_rect(unbounded, perspective_from(10.0f), 64, 48), full);
}

TEST(SceneRect, BoxBesideTheViewOrNoVerticesIsEmpty) {
  const BoundingBox beside{glm::vec3(20.0f, -1.0f, -1.0f), glm::vec3(22.0f, 1.0f, 1.0f), false};
  EXPECT_EQ(projected_scene_rect(beside, perspective_from(10.0f), 64, 64).pixels(), 0u);
  EXPECT_EQ(projected_scene_rect(BoundingBox{}, perspective_from(10.0f), 64, 64).pixels(), 0u);
}

// --- every technique, scissored and not -----------------------------------

constexpr int kSize = 48;

// The spheres scene seen from three times its framing distance (it covers
// about a ninth of the image), its centre moved to NDC `offset`.
glm::mat4 far_view(const Scene& scene, glm::vec2 offset) {
  const float distance = -glm::vec3(scene.camera.view * glm::vec4(scene.bounds().center, 1.0f)).z;
  const float half_view = 3.0f * distance * std::tan(glm::radians(22.5f));  // at three times the distance
  return glm::translate(glm::mat4(1.0f), glm::vec3(offset * half_view, -2.0f * distance)) * scene.camera.view;
}

// A technique instance at kSize x kSize.
struct Renderer : test::TechniqueRenderer {
  explicit Renderer(const TechniqueDescriptor& descriptor) : TechniqueRenderer(descriptor, kSize, kSize) {}
};

double max_difference(const Image& a, const Image& b) { return compare_images(a, b).max_abs; }

class EveryTechnique : public ::testing::Test {
 protected:
  void SetUp() override {
    test::gl_context();
    scene_ = load_scene("spheres", {{"slices", "16"}, {"stacks", "8"}});
    gpu_ = std::make_unique<SceneGpu>(scene_);
    const float distance = -glm::vec3(scene_.camera.view * glm::vec4(scene_.bounds().center, 1.0f)).z;
    projection_ = glm::perspective(glm::radians(45.0f), 1.0f, 0.05f * distance, 10.0f * distance);
  }
  Scene scene_;
  std::unique_ptr<SceneGpu> gpu_;
  glm::mat4 projection_;
};

TEST_F(EveryTechnique, SameImageWithTheRectangleAsWithoutFrameAfterFrameAsItMoves) {
  // Large and centred, then small in a corner, then elsewhere: what a
  // technique left outside one frame's rectangle must not show up in the next.
  const std::vector<glm::vec2> offsets = {{0.0f, 0.0f}, {0.7f, 0.6f}, {-0.6f, -0.5f}};
  const glm::vec3 background(0.2f, 0.4f, 0.6f);
  const TechniqueDescriptor& reference = builtin_techniques().reference();
  Renderer exact(reference);
  for (const TechniqueDescriptor& descriptor : builtin_techniques().all()) {
    SCOPED_TRACE(descriptor.id);
    ASSERT_EQ(supports(descriptor, test::resolved_params(descriptor, {}, kSize, kSize), test::gl_context().device(),
                       SceneFacts{scene_.triangle_count(), scene_.object_count, true}),
              "");
    Renderer on(descriptor), off(descriptor);
    for (size_t i = 0; i < offsets.size(); ++i) {
      SCOPED_TRACE("frame " + std::to_string(i));
      const glm::mat4 view = i == 0 ? scene_.camera.view : far_view(scene_, offsets[i]);
      ScreenRect rect;
      const Image scissored = on.render(*gpu_, view, projection_, background, true, &rect);
      const Image full = off.render(*gpu_, view, projection_, background, false);
      if (i > 0) {
        EXPECT_GT(rect.pixels(), 0u);
        EXPECT_LT(rect.pixels(), uint64_t(kSize * kSize) / 3);  // the rectangle really saves
      }
      EXPECT_LE(max_difference(scissored, full), 1e-5);
      if (held_to_reference(descriptor.exactness, on.technique->counters().fragments_dropped)) {
        const Image truth = exact.render(*gpu_, view, projection_, background, false);
        EXPECT_LE(max_difference(scissored, truth), descriptor.exact_tolerance);
      }
    }
  }
}

TEST_F(EveryTechnique, SceneOutsideTheViewLeavesTheBackground) {
  const glm::vec3 background(0.25f, 0.5f, 0.75f);
  const glm::mat4 beside = glm::translate(glm::mat4(1.0f), glm::vec3(50.0f, 0.0f, 0.0f)) * scene_.camera.view;
  ASSERT_EQ(projected_scene_rect(gpu_->bounding_box(), projection_ * beside, kSize, kSize).pixels(), 0u);
  for (const TechniqueDescriptor& descriptor : builtin_techniques().all()) {
    SCOPED_TRACE(descriptor.id);
    Renderer on(descriptor), off(descriptor);
    // A first frame that draws, so that an empty second one has something to leave behind.
    on.render(*gpu_, scene_.camera.view, projection_, background, true);
    ScreenRect rect{1, 1, 1, 1};
    const Image image = on.render(*gpu_, beside, projection_, background, true, &rect);
    EXPECT_EQ(rect.pixels(), 0u);
    double off_background = 0.0;
    for (size_t p = 0; p < image.rgba.size(); p += 4)
      for (int c = 0; c < 4; ++c)
        off_background = std::max(off_background, double(std::abs(image.rgba[p + size_t(c)] -
                                                                  (c < 3 ? background[c] : 0.0f))));
    EXPECT_EQ(off_background, 0.0);
    EXPECT_LE(max_difference(image, off.render(*gpu_, beside, projection_, background, false)), 1e-5);
  }
}

// Through Harness::run: the RunSpec switch, the saved pixels in work_saved,
// the CSV column, and the same image.
TEST(SceneRectRun, HarnessCountsThePixelsOutsideAndKeepsTheImage) {
  RunSpec spec = test::one_frame("linked_list", {}, "particles", {{"slices", "6"}, {"stacks", "4"}}, 32);
  const RunResult on = test::harness().run(spec);
  spec.scene_rect = false;
  const RunResult off = test::harness().run(spec);
  ASSERT_EQ(on.status, RunStatus::ok) << on.message;
  ASSERT_EQ(off.status, RunStatus::ok) << off.message;
  // The technique's own work_saved figures come first; the harness adds its count last, and only when on.
  ASSERT_FALSE(on.counters.work_saved.empty());
  EXPECT_EQ(on.counters.work_saved.back().name, "pixels_outside_scene_rect");
  EXPECT_GT(on.counters.work_saved.back().value, 0.0);
  EXPECT_LT(on.counters.work_saved.back().value, 32.0 * 32.0);
  for (const auto& [name, value, combine] : off.counters.work_saved) EXPECT_NE(name, "pixels_outside_scene_rect");
  EXPECT_EQ(max_difference(on.image, off.image), 0.0);
  EXPECT_LE(on.error->max_abs, 1e-5);
  const RunContext context{"device", "version", "platform", "rev", "time"};
  const auto& columns = csv_columns();
  const size_t column = size_t(std::find(columns.begin(), columns.end(), "scene_rect") - columns.begin());
  EXPECT_EQ(csv_rows(on, context)[0][column], "on");
  EXPECT_EQ(csv_rows(off, context)[0][column], "off");
}

TEST(SceneRectSweep, BenchSweepsOnAndOff) {
  SweepOptions options;
  options.techniques = {"unsorted"};
  options.scene_rects = {"on", "off"};
  const auto runs = expand_sweep(options, builtin_techniques());
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_TRUE(runs[0].scene_rect);
  EXPECT_FALSE(runs[1].scene_rect);
  options.scene_rects = {"maybe"};
  EXPECT_THROW(expand_sweep(options, builtin_techniques()), std::invalid_argument);
}

}  // namespace
}  // namespace oit
