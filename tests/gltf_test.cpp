// A glTF 2.0 file written here (two overlapping unlit translucent quads, one
// placed by its node's translation, seen by an orthographic camera) renders
// exactly: each region equals the double-precision composite of its layers.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <tuple>

#include "tests/gl_fixture.h"
#include "scenes/scene_library.h"

namespace oit {
namespace {

const std::string kDir = std::string(OIT_BINARY_DIR) + "/test_output/gltf";

struct Layer {
  glm::vec4 color;
  float x_min, x_max;  // in view space (the orthographic camera spans -1..1)
};
// Near quad on the left 3/4, far quad on the right 3/4; they overlap in the middle.
const Layer kNear{{0.9f, 0.2f, 0.1f, 0.6f}, -1.5f, 0.5f};
const Layer kFar{{0.1f, 0.3f, 0.8f, 0.45f}, -0.5f, 1.5f};

// Writes quads.gltf + quads.bin. The near quad's vertices sit at z = -2; the
// far quad's at z = 0, moved to z = -4 by its node. The camera looks down -z.
std::string write_two_quads_gltf() {
  std::filesystem::create_directories(kDir);
  std::vector<float> positions;
  for (const Layer* layer : {&kNear, &kFar}) {
    const float z = layer == &kNear ? -2.0f : 0.0f;
    const float corners[4][2] = {{layer->x_min, -1.5f}, {layer->x_max, -1.5f}, {layer->x_max, 1.5f}, {layer->x_min, 1.5f}};
    for (const auto& c : corners) positions.insert(positions.end(), {c[0], c[1], z});
  }
  const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
  std::string bin(positions.size() * 4 + sizeof(indices), '\0');
  std::memcpy(bin.data(), positions.data(), positions.size() * 4);
  std::memcpy(bin.data() + positions.size() * 4, indices, sizeof(indices));
  std::ofstream(kDir + "/quads.bin", std::ios::binary) << bin;

  using nlohmann::json;
  auto material = [](const glm::vec4& c) {
    return json{{"pbrMetallicRoughness", {{"baseColorFactor", {c.r, c.g, c.b, c.a}}}},
                {"alphaMode", "BLEND"},
                {"extensions", {{"KHR_materials_unlit", json::object()}}}};
  };
  auto mesh = [](int position_accessor, int material_index) {
    return json{{"primitives", {{{"attributes", {{"POSITION", position_accessor}}}, {"indices", 2}, {"material", material_index}}}}};
  };
  auto positions_accessor = [](int view, float z) {
    return json{{"bufferView", view}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
                {"min", {-1.5, -1.5, z}}, {"max", {1.5, 1.5, z}}};
  };
  const json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"KHR_materials_unlit"}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0, 1, 2}}}}},
      {"nodes", {{{"mesh", 0}}, {{"mesh", 1}, {"translation", {0.0, 0.0, -4.0}}}, {{"camera", 0}}}},
      {"cameras", {{{"type", "orthographic"}, {"orthographic", {{"xmag", 1.0}, {"ymag", 1.0}, {"znear", 0.1}, {"zfar", 10.0}}}}}},
      {"meshes", {mesh(0, 0), mesh(1, 1)}},
      {"materials", {material(kNear.color), material(kFar.color)}},
      {"accessors", {positions_accessor(0, -2.0f), positions_accessor(1, 0.0f),
                     {{"bufferView", 2}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                       {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 48}},
                       {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 12}}}},
      {"buffers", {{{"uri", "quads.bin"}, {"byteLength", bin.size()}}}},
  };
  const std::string path = kDir + "/quads.gltf";
  std::ofstream(path) << gltf.dump(2);
  return path;
}

// Front-to-back composite in double, in the reference's operation order.
glm::vec4 composite(const std::vector<glm::vec4>& front_to_back) {
  double acc[3] = {0, 0, 0}, transmittance = 1.0;
  for (const glm::vec4& c : front_to_back) {
    const double weight = transmittance * double(c.a);
    for (int i = 0; i < 3; ++i) acc[i] += weight * double(c[i]);
    transmittance *= 1.0 - double(c.a);
  }
  return glm::vec4(float(acc[0]), float(acc[1]), float(acc[2]), float(1.0 - transmittance));
}

TEST(Gltf, UnlitQuadsUnderAnOrthographicCameraRenderExactly) {
  const std::string path = write_two_quads_gltf();
  const int size = 64;
  const RunResult r = test::render_once("reference", {}, path, {}, size, size);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_EQ(r.max_depth_complexity, 2u);
  size_t mismatches = 0;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float view_x = -1.0f + (float(x) + 0.5f) * 2.0f / float(size);
      std::vector<glm::vec4> layers;
      if (view_x < kNear.x_max) layers.push_back(kNear.color);
      if (view_x > kFar.x_min) layers.push_back(kFar.color);
      const glm::vec4 expected = composite(layers);
      for (int c = 0; c < 4; ++c) mismatches += r.image.at(x, y, c) != expected[c];
    }
  }
  EXPECT_EQ(mismatches, 0u);
  // Unsorted blending submits near before far, so it is wrong where they overlap.
  const RunResult unsorted = test::render_once("unsorted", {}, path, {}, size, size);
  EXPECT_GT(unsorted.error->max_abs, 0.05);
}

// One quad mesh used by three nodes (instancing), unsigned-byte indices, no
// normals, an alphaMode MASK material, and an orthographic camera placed by
// its node: three object ids, computed normals, alpha 1 (0.7 >= cutoff 0.5).
std::string write_instanced_gltf() {
  using nlohmann::json;
  const json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0, 4}}}}},
      // A parent moves all instances by z = -2; the children place them side by side.
      {"nodes", {{{"children", {1, 2, 3}}, {"translation", {0.0, 0.0, -2.0}}},
                 {{"mesh", 0}, {"translation", {-0.6, 0.0, 0.0}}},
                 {{"mesh", 0}, {"translation", {0.6, 0.0, -0.5}}},
                 {{"mesh", 0}, {"translation", {0.0, 0.3, -1.0}}, {"scale", {2.0, 2.0, 2.0}}},
                 {{"camera", 0}, {"translation", {0.0, 0.0, 1.0}}}}},
      {"cameras", {{{"type", "orthographic"}, {"orthographic", {{"xmag", 1.5}, {"ymag", 1.2}, {"znear", 0.5}, {"zfar", 20.0}}}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"material", 0}}}}}}},
      {"materials", {{{"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.7, 0.3, 0.7}}}},
                      {"alphaMode", "MASK"},
                      {"alphaCutoff", 0.5}}}},
  };
  return test::write_mesh_gltf("gltf", "instanced", gltf,
                               {-0.5f, -0.5f, 0.0f, 0.5f, -0.5f, 0.0f, 0.5f, 0.5f, 0.0f, -0.5f, 0.5f, 0.0f},
                               {0, 1, 2, 0, 2, 3}, 5121);  // unsigned byte
}

TEST(Gltf, InstancesAreObjectsAndTheOrthographicCameraIsPlacedByItsNode) {
  const std::string path = write_instanced_gltf();
  const Scene scene = load_scene(path, {});
  EXPECT_EQ(scene.object_count, 3u);
  EXPECT_EQ(scene.vertices.size(), 12u);
  ASSERT_EQ(scene.triangle_count(), 6u);
  EXPECT_TRUE(scene.lit);
  for (size_t v = 0; v < scene.vertices.size(); ++v) {
    const Vertex& vertex = scene.vertices[v];
    EXPECT_EQ(vertex.object_id, uint32_t(v / 4)) << v;
    EXPECT_EQ(vertex.surface_id, uint32_t(v / 4)) << v;
    EXPECT_EQ(vertex.color, glm::vec4(0.2f, 0.7f, 0.3f, 1.0f)) << v;  // MASK above the cutoff: opaque
    EXPECT_NEAR(glm::distance(vertex.normal, glm::vec3(0.0f, 0.0f, 1.0f)), 0.0f, 1e-6f) << v;
  }
  // World transforms: parent then child (the third instance also scaled by 2).
  EXPECT_LT(glm::distance(scene.vertices[0].position, glm::vec3(-1.1f, -0.5f, -2.0f)), 1e-6f);
  EXPECT_LT(glm::distance(scene.vertices[4].position, glm::vec3(0.1f, -0.5f, -2.5f)), 1e-6f);
  EXPECT_LT(glm::distance(scene.vertices[8].position, glm::vec3(-1.0f, -0.7f, -3.0f)), 1e-6f);
  ASSERT_TRUE(scene.camera.orthographic);
  EXPECT_FLOAT_EQ(scene.camera.xmag, 1.5f);
  EXPECT_FLOAT_EQ(scene.camera.ymag, 1.2f);
  EXPECT_FLOAT_EQ(scene.camera.znear, 0.5f);
  EXPECT_FLOAT_EQ(scene.camera.zfar, 20.0f);
  const glm::vec4 eye_space = scene.camera.view * glm::vec4(0.0f, 0.0f, -2.0f, 1.0f);
  EXPECT_NEAR(eye_space.z, -3.0f, 1e-6f);  // the camera node sits at z = +1
  // The big third instance lies behind the other two where they overlap it:
  // up to 2 layers, and opaque layers hide what is behind them exactly.
  const RunResult r = test::render_once("reference", {}, path, {}, 48, 48);
  EXPECT_EQ(r.max_depth_complexity, 2u);
  const RunResult unsorted = test::render_once("unsorted", {}, path, {}, 48, 48);
  EXPECT_GT(unsorted.error->max_abs, 0.0);  // back-to-front is required even when opaque
}

// Two lit quads (no normals, no camera: face normals and the framing camera)
// under one node named "model" with `placement` (scale, translation, ...).
std::string write_placed_quads_gltf(const std::string& name, const nlohmann::json& placement) {
  using nlohmann::json;
  json node = placement;
  node["mesh"] = 0;
  node["name"] = "model";
  const json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {node}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"material", 0}}}}}}},
      {"materials", {{{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.3, 0.2, 0.5}}}}, {"alphaMode", "BLEND"}}}},
  };
  return test::write_mesh_gltf("gltf", name, gltf,
                               {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0,
                                -1, -1, -0.5f, 1, -1, -0.5f, 1, 1, -0.5f, -1, 1, -0.5f},
                               {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7}, 5125);
}

// A huge but finite scale: face normals were computed in float, whose
// squared cross product overflowed at a scale of 1e10 (NaN pixels, status
// ok). The framing camera makes the image the same as at scale 1.
TEST(Gltf, AHugeButUsableScaleRendersTheImageOfScaleOne) {
  const RunResult one = test::render_once("reference", {}, write_placed_quads_gltf("scale_1", nlohmann::json::object()),
                                          {}, 32, 32);
  const RunResult huge =
      test::render_once("reference", {}, write_placed_quads_gltf("scale_1e15", {{"scale", {1e15, 1e15, 1e15}}}), {},
                        32, 32);
  ASSERT_EQ(huge.status, RunStatus::ok) << huge.message;
  for (float v : huge.image.rgba) ASSERT_TRUE(std::isfinite(v));
  EXPECT_GT(huge.max_depth_complexity, 0u);
  EXPECT_LT(test::max_abs_difference(one.image, huge.image), 1e-4);
}

// Transforms that leave positions finite but the scene unusable in float
// (gone from the image, or collapsed) are refused naming the node and the fix.
TEST(Gltf, NodeTransformsThatBreakFloatRenderingAreRefusedNamingTheNode) {
  const std::vector<std::tuple<std::string, nlohmann::json, std::string>> cases = {
      {"scale_1e20", {{"scale", {1e20, 1e20, 1e20}}}, "puts vertices 1e+20 from the origin"},
      {"scale_1e30", {{"scale", {1e30, 1e30, 1e30}}}, "scale the model down"},
      {"scale_1e40", {{"scale", {1e40, 1e40, 1e40}}}, "makes vertex positions non-finite"},  // past float
      {"matrix_1e30", {{"matrix", {1e30, 0, 0, 0, 0, 1e30, 0, 0, 0, 0, 1e30, 0, 0, 0, 0, 1}}}, "scale the model down"},
      {"scale_1e-30", {{"scale", {1e-30, 1e-30, 1e-30}}}, "scale the model up"},
      {"scale_1e-20", {{"scale", {1e-20, 1e-20, 1e-20}}}, "less than the 1e-16 that rendering in float resolves"},
      {"translation_1e8", {{"translation", {1e8, 0, 0}}}, "move it nearer the origin"},
  };
  for (const auto& [name, placement, problem] : cases) {
    const std::string path = write_placed_quads_gltf(name, placement);
    try {
      load_scene(path, {});
      ADD_FAILURE() << name << " was accepted";
    } catch (const std::invalid_argument& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
      EXPECT_NE(message.find("node 0 'model'"), std::string::npos) << message;
      EXPECT_NE(message.find(problem), std::string::npos) << message;
    }
  }
  // Far from the origin but still resolved: accepted.
  EXPECT_NO_THROW(load_scene(write_placed_quads_gltf("translation_1e4", {{"translation", {1e4, 0, 0}}}), {}));
}

TEST(Gltf, MalformedFilesGiveErrorsNamingTheFile) {
  std::filesystem::create_directories(kDir);
  const std::string path = kDir + "/broken.gltf";
  std::ofstream(path) << "{ \"asset\": {\"version\": \"2.0\"}, \"meshes\": [ ";
  RunSpec spec;
  spec.technique = "unsorted";
  spec.scene = path;
  spec.width = spec.height = 8;
  const RunResult r = test::harness().run(spec);
  EXPECT_EQ(r.status, RunStatus::error);
  EXPECT_NE(r.message.find("broken.gltf"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace oit
