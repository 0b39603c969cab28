// A glTF 2.0 file written here (two overlapping unlit translucent quads, one
// placed by its node's translation, seen by an orthographic camera) renders
// exactly: each region equals the double-precision composite of its layers.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "gl_fixture.h"

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
