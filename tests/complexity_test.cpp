// Depth complexity statistics (histogram, complexity coverage Psi of
// pastyrik2016, heatmap) against hand-computed values, and the camera specs
// (seeded random viewpoints, max_list) through the harness.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <limits>
#include <stdexcept>

#include "harness/app/sweep.h"
#include "scenes/cameras.h"
#include "harness/run/complexity.h"
#include "harness/output/heatmap.h"
#include "tests/gl_fixture.h"
#include "scenes/scene_library.h"

namespace oit {
namespace {

DepthComplexity from_counts(std::vector<uint32_t> counts, int width) {
  DepthComplexity c;
  c.width = width;
  c.height = int(counts.size()) / width;
  c.per_pixel = std::move(counts);
  summarize_depth_complexity(c);
  return c;
}

TEST(Complexity, HistogramAndPsiOfHandMadeCounts) {
  const DepthComplexity c = from_counts({0, 0, 1, 2, 3, 3}, 3);
  EXPECT_EQ(c.fragments, 9u);
  EXPECT_EQ(c.max, 3u);
  EXPECT_DOUBLE_EQ(c.mean, 1.5);
  EXPECT_EQ(c.covered_pixels, 4u);
  // Longer than 2/3 of 3 = 2: only the two 3s, of all six pixels.
  EXPECT_DOUBLE_EQ(c.psi, 2.0 / 6.0);
  EXPECT_EQ(list_length_histogram(c), (std::vector<uint64_t>{2, 1, 1, 2}));
  const auto bins = binned_histogram(list_length_histogram(c), 2);
  ASSERT_EQ(bins.size(), 2u);
  EXPECT_EQ(bins[0].first, 0u);
  EXPECT_EQ(bins[0].last, 1u);
  EXPECT_EQ(bins[0].pixels, 3u);
  EXPECT_EQ(bins[1].first, 2u);
  EXPECT_EQ(bins[1].last, 3u);
  EXPECT_EQ(bins[1].pixels, 3u);
  EXPECT_EQ(binned_histogram(list_length_histogram(c), 16).size(), 4u);  // never wider than needed
  // Exactly 2/3 of the longest is not longer: 3 of 6 with max 6 (4 > 4 is false).
  EXPECT_DOUBLE_EQ(from_counts({6, 4, 5, 0}, 2).psi, 0.5);
  // With max 1 every covered pixel counts; an empty view has Psi 0.
  EXPECT_DOUBLE_EQ(from_counts({0, 1, 1, 0}, 2).psi, 0.5);
  EXPECT_DOUBLE_EQ(from_counts({0, 0, 0, 0}, 2).psi, 0.0);
}

// Three unlit quads under an orthographic camera spanning x in [-1, 1]: all
// start at x = -1 and end at -0.5, 0 and 0.5, so the image's four column
// bands hold 3, 2, 1 and 0 layers.
std::string write_banded_gltf() {
  std::vector<float> positions;
  const float ends[3] = {-0.5f, 0.0f, 0.5f};
  for (int q = 0; q < 3; ++q) {
    const float z = -1.0f - float(q);
    const float corners[4][2] = {{-1.5f, -1.5f}, {ends[q], -1.5f}, {ends[q], 1.5f}, {-1.5f, 1.5f}};
    for (const auto& c : corners) positions.insert(positions.end(), {c[0], c[1], z});
  }
  std::vector<uint32_t> indices;
  for (uint32_t q = 0; q < 3; ++q)
    for (uint32_t i : {0, 1, 2, 0, 2, 3}) indices.push_back(4 * q + i);
  using nlohmann::json;
  const json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"KHR_materials_unlit"}},
      {"scenes", {{{"nodes", {0, 1}}}}},
      {"nodes", {{{"mesh", 0}}, {{"camera", 0}}}},
      {"cameras", {{{"type", "orthographic"}, {"orthographic", {{"xmag", 1.0}, {"ymag", 1.0}, {"znear", 0.1}, {"zfar", 10.0}}}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"material", 0}}}}}}},
      {"materials", {{{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.4, 0.2, 0.5}}}},
                      {"alphaMode", "BLEND"},
                      {"extensions", {{"KHR_materials_unlit", json::object()}}}}}},
  };
  return test::write_mesh_gltf("complexity", "bands", gltf, positions, indices, 5123);  // unsigned short
}

TEST(Complexity, KnownLayersGivePsiHistogramAndHeatmap) {
  const Scene scene = load_scene(write_banded_gltf(), {});
  test::gl_context();
  const SceneGpu gpu(scene);
  const int size = 64;
  const DepthComplexity c = measure_depth_complexity(gpu, scene.camera.view, scene.camera.projection(1.0f), size, size);
  EXPECT_EQ(c.max, 3u);
  EXPECT_DOUBLE_EQ(c.mean, 1.5);
  EXPECT_EQ(c.covered_pixels, 3u * 16u * 64u);
  EXPECT_DOUBLE_EQ(c.psi, 0.25);  // only the 3-layer band is longer than 2
  EXPECT_EQ(list_length_histogram(c), (std::vector<uint64_t>{1024, 1024, 1024, 1024}));
  const Image heat = list_length_heatmap(c);
  ASSERT_EQ(heat.width, size);
  // Left band: the longest list, viridis's top (yellow #fde725); right
  // band: empty, its bottom (purple #440154); linear values in the image.
  const float top[3] = {0.993248f, 0.906157f, 0.143936f}, bottom[3] = {0.267004f, 0.004874f, 0.329415f};
  for (int ch = 0; ch < 3; ++ch) {
    EXPECT_NEAR(heat.at(2, 30, ch), srgb_decode(top[ch]), 1e-6f) << ch;
    EXPECT_NEAR(heat.at(60, 30, ch), srgb_decode(bottom[ch]), 1e-6f) << ch;
  }
  EXPECT_EQ(list_length_scale(c).high, 3.0f);
  // The harness reports the same Psi for a run.
  const RunResult r = test::render_once("reference", {}, write_banded_gltf(), {}, size, size);
  EXPECT_DOUBLE_EQ(r.psi, 0.25);
}

TEST(Complexity, HeatmapRangeMapsLowToTheBottomHighToTheTopAndNanToBlack) {
  // The signed range of a diagnostic field (e.g. kappa in [-1, 1]): -1, 0
  // and 1 are viridis at 0, 1/2 and 1 (#440154, #21918c, #fde725), NaN is
  // black, 5 is clamped to the top.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const Image heat = heatmap_range({-1.0f, 0.0f, 1.0f, nan, 5.0f}, 5, 1, -1.0f, 1.0f);
  const float srgb[5][3] = {{0.267004f, 0.004874f, 0.329415f}, {0.127568f, 0.566949f, 0.550556f},
                            {0.993248f, 0.906157f, 0.143936f}, {0.0f, 0.0f, 0.0f},
                            {0.993248f, 0.906157f, 0.143936f}};
  ASSERT_EQ(heat.rgba.size(), 20u);
  for (int p = 0; p < 5; ++p) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(heat.at(p, 0, c), srgb_decode(srgb[p][c]), 1e-6f) << p << " " << c;
    EXPECT_EQ(heat.at(p, 0, 3), 1.0f);
  }
  EXPECT_THROW(heatmap_range({0.0f}, 2, 1, 0.0f, 1.0f), std::invalid_argument);
}

TEST(Cameras, SpecsParseExpandAndRefuseNonsense) {
  EXPECT_EQ(expand_camera_spec("default"), (std::vector<std::string>{"default"}));
  EXPECT_EQ(expand_camera_spec("random:3:7"),
            (std::vector<std::string>{"random:3:7@0", "random:3:7@1", "random:3:7@2"}));
  EXPECT_EQ(expand_camera_spec("random:3:7@1"), (std::vector<std::string>{"random:3:7@1"}));
  EXPECT_EQ(expand_camera_spec("max_list"), (std::vector<std::string>{"max_list:16:1"}));
  EXPECT_EQ(parse_camera_spec("max_list:5:9").count, 5u);
  for (const char* bad : {"", "front", "random", "random:3", "random:0:1", "random:3:x", "random:3:1@3",
                          "random:-2:1", "max_list:4", "max_list:4:1@0", "random:3:1@"}) {
    EXPECT_THROW(parse_camera_spec(bad), std::invalid_argument) << bad;
  }
}

TEST(Cameras, RandomViewpointsAreSeededAndFrameTheBoundingSphere) {
  const BoundingSphere sphere{glm::vec3(1.0f, -2.0f, 3.0f), 2.5f};
  const Camera a = random_viewpoint(sphere, 7, 2);
  EXPECT_EQ(a.view, random_viewpoint(sphere, 7, 2).view);  // reproducible, bit for bit
  EXPECT_NE(a.view, random_viewpoint(sphere, 8, 2).view);  // another seed, another view
  EXPECT_NE(a.view, random_viewpoint(sphere, 7, 3).view);
  // Viewpoint I does not depend on the set size.
  const Scene scene = load_scene("spheres", {{"count", "2"}, {"slices", "8"}, {"stacks", "4"}});
  EXPECT_EQ(camera_for_spec(scene, parse_camera_spec("random:4:7@2")).view,
            camera_for_spec(scene, parse_camera_spec("random:9:7@2")).view);
  // The centre is straight ahead at the distance where the sphere fills the view.
  for (uint32_t i = 0; i < 20; ++i) {
    const Camera c = random_viewpoint(sphere, 11, i);
    const glm::vec4 centre = c.view * glm::vec4(sphere.center, 1.0f);
    const float distance = sphere.radius / std::sin(c.yfov_radians * 0.5f);
    EXPECT_NEAR(centre.x, 0.0f, 1e-4f);
    EXPECT_NEAR(centre.y, 0.0f, 1e-4f);
    EXPECT_NEAR(-centre.z, distance, 1e-3f);
    EXPECT_LT(c.znear, distance - sphere.radius);
    EXPECT_GT(c.zfar, distance + sphere.radius);
  }
  // Twenty viewpoints spread over the sphere: both hemispheres in every axis.
  glm::vec3 low(1.0f), high(-1.0f);
  for (uint32_t i = 0; i < 20; ++i) {
    const glm::vec3 eye = glm::vec3(glm::inverse(random_viewpoint(sphere, 11, i).view)[3]);
    low = glm::min(low, glm::normalize(eye - sphere.center));
    high = glm::max(high, glm::normalize(eye - sphere.center));
  }
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_LT(low[axis], -0.3f);
    EXPECT_GT(high[axis], 0.3f);
  }
}

TEST(Cameras, MaxListPicksTheViewpointWithTheLongestList) {
  const Scene scene = load_scene("spheres", {{"count", "3"}, {"slices", "12"}, {"stacks", "6"}});
  test::gl_context();
  const SceneGpu gpu(scene);
  const CameraSpec spec = parse_camera_spec("max_list:8:3");
  const ChosenViewpoint chosen = choose_max_list_camera(gpu, spec, 48);
  uint32_t longest = 0;
  for (uint32_t i = 0; i < 8; ++i) {
    const Camera c = random_viewpoint(scene.bounds(), 3, i);
    longest = std::max(longest, measure_depth_complexity(gpu, c.view, c.projection(1.0f), 48, 48).max);
  }
  EXPECT_EQ(chosen.max_list, longest);
  EXPECT_EQ(chosen.camera.view, random_viewpoint(scene.bounds(), 3, chosen.index).view);
  EXPECT_GE(longest, 4u);  // some view looks through at least two spheres
}

TEST(Cameras, HarnessRunsUseTheCameraForImageReferenceAndComplexity) {
  const RawParams spheres = {{"count", "3"}, {"slices", "12"}, {"stacks", "6"}};
  RunSpec spec = test::one_frame("reference", {}, "spheres", spheres, 32);
  const RunResult plain = test::harness().run(spec);
  spec.camera = "random:4:2@1";
  const RunResult moved = test::harness().run(spec);
  ASSERT_EQ(moved.status, RunStatus::ok) << moved.message;
  EXPECT_EQ(moved.error->max_abs, 0.0);  // compared with the reference of the same view
  EXPECT_GT(compare_images(plain.image, moved.image).max_abs, 0.05);
  EXPECT_EQ(compare_images(moved.image, test::harness().reference_image("spheres", spheres, 32, 32, glm::vec3(0.0f),
                                                                        "random:4:2@1"))
                .max_abs,
            0.0);
  // Unsorted blending is wrong against the moved reference too, so the camera reaches the technique.
  spec.technique = "unsorted";
  EXPECT_GT(test::harness().run(spec).error->max_abs, 0.0);
  spec.camera = "max_list:4:2";
  EXPECT_EQ(test::harness().run(spec).status, RunStatus::ok);
  spec.camera = "random:4:2";  // a set is not one run
  const RunResult set = test::harness().run(spec);
  EXPECT_EQ(set.status, RunStatus::error);
  EXPECT_NE(set.message.find("set of viewpoints"), std::string::npos) << set.message;
}

TEST(Cameras, SweepsExpandRandomSetsIntoOneRunPerViewpoint) {
  SweepOptions options;
  options.techniques = {"unsorted"};
  options.cameras = {"default", "random:2:5"};
  const auto runs = expand_sweep(options, builtin_techniques());
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[0].camera, "default");
  EXPECT_EQ(runs[1].camera, "random:2:5@0");
  EXPECT_EQ(runs[2].camera, "random:2:5@1");
  RunResult r;
  r.spec = runs[2];
  EXPECT_EQ(run_label(r), "unsorted_quads_256x256_camera-random-2-5-1");
  options.cameras = {"sideways"};
  EXPECT_THROW(expand_sweep(options, builtin_techniques()), std::invalid_argument);
}

}  // namespace
}  // namespace oit
