// The synthetic scenes: what each promises about its geometry, curvature,
// depth complexity and submission order.
#include <gtest/gtest.h>

#include <set>

#include "harness/run/complexity.h"
#include "tests/gl_fixture.h"
#include "scenes/scene_library.h"

namespace oit {
namespace {

DepthComplexity complexity_of(const Scene& scene, int size) {
  test::gl_context();
  SceneGpu gpu(scene);
  return measure_depth_complexity(gpu, scene.camera.view, scene.camera.projection(1.0f), size, size);
}

TEST(Scenes, EveryLibrarySceneBuildsValidWithDefaults) {
  for (const auto& descriptor : scene_library()) {
    const Scene scene = load_scene(descriptor.id, {});
    EXPECT_GT(scene.triangle_count(), 0u) << descriptor.id;
    EXPECT_GE(scene.object_count, 1u) << descriptor.id;
    EXPECT_NO_THROW(scene.validate()) << descriptor.id;
  }
}

TEST(Scenes, TorusCurvatureIsTheAnalyticMeanCurvature) {
  const Scene torus = load_scene("torus", {{"slices", "16"}, {"stacks", "8"}});
  ASSERT_TRUE(torus.analytic_curvature);
  // R = 1, r = 0.35: outer equator (R + 2r)/(2r(R + r)), inner (R - 2r)/(2r(R - r)).
  const float outer = (1.0f + 0.7f) / (0.7f * 1.35f), inner = (1.0f - 0.7f) / (0.7f * 0.65f);
  float lowest = 1e9f, highest = -1e9f;
  for (const Vertex& v : torus.vertices) {
    lowest = std::min(lowest, v.mean_curvature);
    highest = std::max(highest, v.mean_curvature);
  }
  EXPECT_NEAR(highest, outer, 1e-4);
  EXPECT_NEAR(lowest, inner, 1e-4);
  // Sphere: 1/r everywhere.
  const Scene nested = load_scene("nested_spheres", {{"count", "2"}, {"slices", "8"}, {"stacks", "4"}});
  std::set<float> curvatures;
  for (const Vertex& v : nested.vertices) curvatures.insert(v.mean_curvature);
  EXPECT_EQ(curvatures, (std::set<float>{1.0f, 2.0f}));
}

TEST(Scenes, NestedSpheresHaveTwoLayersPerSphereAtTheCentre) {
  const Scene scene = load_scene("nested_spheres", {{"count", "3"}});
  const DepthComplexity c = complexity_of(scene, 33);
  EXPECT_EQ(c.per_pixel[size_t(16 * 33 + 16)], 6u);
  EXPECT_EQ(c.max, 6u);
}

TEST(Scenes, RandomQuadsDepthComplexityFollowsCountAndSize) {
  const Scene scene = load_scene("random_quads", {{"count", "64"}, {"size", "0.5"}});
  const DepthComplexity c = complexity_of(scene, 64);
  // Expected mean about count * size^2 = 16 (quads near the border spill out).
  EXPECT_GT(c.mean, 8.0);
  EXPECT_LT(c.mean, 20.0);
  EXPECT_EQ(scene.object_count, 64u);
}

TEST(Scenes, RandomQuadsOrderControlsSubmissionNotTheImage) {
  auto depths = [](const std::string& order) {
    const Scene s = load_scene("random_quads", {{"count", "16"}, {"order", order}});
    std::vector<float> d;
    for (size_t t = 0; t < s.triangle_count(); t += 2) d.push_back(-s.vertices[s.indices[3 * t]].position.z);
    return d;
  };
  const auto front = depths("front_to_back"), back = depths("back_to_front");
  EXPECT_TRUE(std::is_sorted(front.begin(), front.end()));
  EXPECT_TRUE(std::is_sorted(back.rbegin(), back.rend()));
  EXPECT_FALSE(std::is_sorted(depths("random").begin(), depths("random").end()));
  EXPECT_THROW(load_scene("random_quads", {{"order", "sideways"}}), std::invalid_argument);
  // Same geometry, other order: the exact image does not change.
  const RunResult a = test::render_once("reference", {}, "random_quads", {{"count", "16"}, {"order", "front_to_back"}}, 32, 32);
  const RunResult b = test::render_once("reference", {}, "random_quads", {{"count", "16"}, {"order", "back_to_front"}}, 32, 32);
  EXPECT_EQ(compare_images(a.image, b.image).max_abs, 0.0);
}

TEST(Scenes, ParticlesAreSeparateObjects) {
  const Scene scene = load_scene("particles", {{"per_axis", "3"}});
  EXPECT_EQ(scene.object_count, 27u);
  std::set<uint32_t> ids;
  for (const Vertex& v : scene.vertices) ids.insert(v.object_id);
  EXPECT_EQ(ids.size(), 27u);
}

TEST(Scenes, ContentHashIsStableAndSeesChanges) {
  // The hash keys cached references: equal scenes must hash equal (no
  // padding bytes), different ones differently.
  EXPECT_EQ(load_scene("quads", {}).content_hash(), load_scene("quads", {}).content_hash());
  EXPECT_EQ(load_scene("spheres", {}).content_hash(), load_scene("spheres", {}).content_hash());
  EXPECT_NE(load_scene("quads", {}).content_hash(), load_scene("quads", {{"seed", "2"}}).content_hash());
  Scene moved = load_scene("quads", {});
  moved.camera.znear *= 2.0f;
  EXPECT_NE(moved.content_hash(), load_scene("quads", {}).content_hash());
}

TEST(Scenes, ReorderingKeepsStableTriangleIds) {
  Scene scene = load_scene("spheres", {{"count", "1"}, {"slices", "6"}, {"stacks", "4"}});
  const Scene original = scene;
  reorder_triangles(scene, "shuffled:5");
  ASSERT_EQ(scene.triangle_count(), original.triangle_count());
  EXPECT_NE(scene.indices, original.indices);
  for (size_t t = 0; t < scene.triangle_count(); ++t) {
    const uint32_t id = scene.triangle_ids[t];
    for (int k = 0; k < 3; ++k) EXPECT_EQ(scene.indices[3 * t + k], original.indices[3 * id + k]);
  }
  EXPECT_THROW(reorder_triangles(scene, "sideways"), std::invalid_argument);
}

}  // namespace
}  // namespace oit
