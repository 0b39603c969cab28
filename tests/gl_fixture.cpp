#include "tests/gl_fixture.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include "harness/output/image.h"
#include "harness/run/prepared_run.h"
#include "harness/gl/check.h"
#include "scenes/scene.h"
#include "scenes/scene_library.h"

namespace oit::test {

GlContext& gl_context() {
  static std::unique_ptr<GlContext> context = create_headless_context();
  return *context;
}

Harness& harness() {
  static Harness instance(gl_context(), builtin_techniques());
  return instance;
}

glm::vec4 drawn_texel(const Program& program) {
  gl_context();
  Texture color = make_texture_2d(GL_RGBA32F, 4, 4);
  Framebuffer framebuffer = make_framebuffer();
  glNamedFramebufferTexture(framebuffer.id(), GL_COLOR_ATTACHMENT0, color.id(), 0);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
  glViewport(0, 0, 4, 4);
  glUseProgram(program.id());
  VertexArray empty = make_vertex_array();
  glBindVertexArray(empty.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  const Image image = read_texture_rgba32f(color.id(), 4, 4);
  glBindVertexArray(0);
  glUseProgram(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  gl_check("drawing a test shader full screen");
  return {image.at(2, 2, 0), image.at(2, 2, 1), image.at(2, 2, 2), image.at(2, 2, 3)};
}

RunSpec one_frame(const std::string& technique, const RawParams& params, const std::string& scene,
                  const RawParams& scene_params, int size, const std::string& order) {
  RunSpec spec = single_frame(technique, params, scene, scene_params, size, size);
  spec.submission_order = order;
  // Tests look stages up by the wall clock, which every device has (a GPU
  // would default to gl and record no wall stages).
  spec.clock = ClockKind::wall;
  return spec;
}

double extra_counter(const RunResult& r, const std::string& name) {
  if (auto value = find_figure(r.counters.extra, name)) return *value;
  ADD_FAILURE() << r.spec.technique << " reports no counter '" << name << "'";
  return std::nan("");
}

double work_saved(const RunResult& r, const std::string& name) {
  if (auto value = find_figure(r.counters.work_saved, name)) return *value;
  ADD_FAILURE() << r.spec.technique << " reports no work_saved figure '" << name << "'";
  return std::nan("");
}

RunResult run_ok(const RunSpec& spec) {
  RunResult r = harness().run(spec);
  EXPECT_EQ(r.status, RunStatus::ok) << spec.technique << ": " << r.message;
  EXPECT_TRUE(r.error.has_value()) << spec.technique;
  return r;
}

double max_abs_difference(const Image& a, const Image& b) {
  EXPECT_EQ(a.rgba.size(), b.rgba.size());
  double worst = 0.0;
  for (size_t i = 0; i < a.rgba.size() && i < b.rgba.size(); ++i)
    worst = std::max(worst, std::abs(double(a.rgba[i]) - double(b.rgba[i])));
  return worst;
}

RunResult render_once(const std::string& technique, const RawParams& params, const std::string& scene,
                      const RawParams& scene_params, int width, int height) {
  RunSpec spec = one_frame(technique, params, scene, scene_params, width);
  spec.height = height;
  RunResult result = harness().run(spec);
  EXPECT_EQ(result.status, RunStatus::ok) << technique << ": " << result.message;
  return result;
}

std::string write_test_file(const std::string& folder, const std::string& name, const std::string& bytes) {
  const std::string dir = std::string(OIT_BINARY_DIR) + "/test_output/" + folder;
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + name;
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  return path;
}

std::string write_mesh_gltf(const std::string& folder, const std::string& name, nlohmann::json gltf,
                            const std::vector<float>& positions, const std::vector<uint32_t>& indices, int index_type) {
  const std::map<int, size_t> index_sizes = {{5121, 1}, {5123, 2}, {5125, 4}};
  const size_t index_size = index_sizes.at(index_type);
  const size_t position_bytes = positions.size() * sizeof(float);
  std::string bin(position_bytes + indices.size() * index_size, '\0');
  std::memcpy(bin.data(), positions.data(), position_bytes);
  for (size_t i = 0; i < indices.size(); ++i) {
    if (index_size < 4 && indices[i] >> (8 * index_size) != 0)
      throw std::invalid_argument("index " + std::to_string(indices[i]) + " does not fit glTF componentType " +
                                  std::to_string(index_type));
    // glTF is little-endian, like the machines the tests run on: the index's low bytes.
    std::memcpy(bin.data() + position_bytes + i * index_size, &indices[i], index_size);
  }
  write_test_file(folder, name + ".bin", bin);
  std::vector<float> low(3, INFINITY), high(3, -INFINITY);
  for (size_t i = 0; i < positions.size(); ++i) {
    low[i % 3] = std::min(low[i % 3], positions[i]);
    high[i % 3] = std::max(high[i % 3], positions[i]);
  }
  gltf["accessors"] = {
      {{"bufferView", 0}, {"componentType", 5126}, {"count", positions.size() / 3}, {"type", "VEC3"},
       {"min", low}, {"max", high}},
      {{"bufferView", 1}, {"componentType", index_type}, {"count", indices.size()}, {"type", "SCALAR"}}};
  gltf["bufferViews"] = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", position_bytes}},
                         {{"buffer", 0}, {"byteOffset", position_bytes}, {"byteLength", bin.size() - position_bytes}}};
  gltf["buffers"] = {{{"uri", name + ".bin"}, {"byteLength", bin.size()}}};
  return write_test_file(folder, name + ".gltf", gltf.dump(2));
}

std::string write_quads_gltf(const std::string& folder, const std::string& name,
                             const std::vector<std::pair<float, glm::vec4>>& quads, double znear) {
  std::vector<float> positions;
  for (const auto& quad : quads) {
    const float corners[4][2] = {{-1.5f, -1.5f}, {1.5f, -1.5f}, {1.5f, 1.5f}, {-1.5f, 1.5f}};
    for (const auto& c : corners) positions.insert(positions.end(), {c[0], c[1], quad.first});
  }
  const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
  std::string bin(positions.size() * 4 + sizeof(indices), '\0');
  std::memcpy(bin.data(), positions.data(), positions.size() * 4);
  std::memcpy(bin.data() + positions.size() * 4, indices, sizeof(indices));
  write_test_file(folder, name + ".bin", bin);

  using nlohmann::json;
  json nodes = json::array(), meshes = json::array(), materials = json::array(), accessors = json::array(),
       views = json::array();
  for (size_t i = 0; i < quads.size(); ++i) {
    const glm::vec4& c = quads[i].second;
    const float z = quads[i].first;
    nodes.push_back({{"mesh", i}});
    meshes.push_back({{"primitives", {{{"attributes", {{"POSITION", i}}}, {"indices", quads.size()}, {"material", i}}}}});
    materials.push_back({{"pbrMetallicRoughness", {{"baseColorFactor", {c.r, c.g, c.b, c.a}}}},
                         {"alphaMode", "BLEND"},
                         {"extensions", {{"KHR_materials_unlit", json::object()}}}});
    accessors.push_back({{"bufferView", i}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
                         {"min", {-1.5, -1.5, z}}, {"max", {1.5, 1.5, z}}});
    views.push_back({{"buffer", 0}, {"byteOffset", 48 * i}, {"byteLength", 48}});
  }
  accessors.push_back({{"bufferView", quads.size()}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}});
  views.push_back({{"buffer", 0}, {"byteOffset", 48 * quads.size()}, {"byteLength", 12}});
  nodes.push_back({{"camera", 0}});
  json scene_nodes = json::array();
  for (size_t i = 0; i < nodes.size(); ++i) scene_nodes.push_back(i);
  const json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"KHR_materials_unlit"}},
      {"scene", 0},
      {"scenes", {{{"nodes", scene_nodes}}}},
      {"nodes", nodes},
      {"cameras", {{{"type", "orthographic"}, {"orthographic", {{"xmag", 1.0}, {"ymag", 1.0}, {"znear", znear}, {"zfar", 10.0}}}}}},
      {"meshes", meshes},
      {"materials", materials},
      {"accessors", accessors},
      {"bufferViews", views},
      {"buffers", {{{"uri", name + ".bin"}, {"byteLength", bin.size()}}}},
  };
  return write_test_file(folder, name + ".gltf", gltf.dump(2));
}

std::vector<DiagnosticImage> diagnostic_images_once(const std::string& technique, const RawParams& params,
                                                    const std::string& scene, const RawParams& scene_params,
                                                    int width, int height) {
  gl_context();
  PreparedRun prepared(builtin_techniques(), technique, params);
  const Scene loaded = load_scene(scene, scene_params);
  const SceneGpu gpu(loaded);
  const Camera camera = resolve_camera(gpu, "default");
  prepared.resolve(gl_context().device(), {loaded.triangle_count(), loaded.object_count, true},
                   FrameContent{width, height, 0, 0});
  prepared.create(untiled_plan(width, height));
  RenderTarget target(width, height);
  StageClock clock(ClockKind::wall);
  const Frame frame{gpu, camera.view, camera.projection(float(width) / float(height)), width, height,
                    glm::vec3(0.0f), target.framebuffer.id(), clock};
  prepared.render_frame(frame, false, true);
  return prepared.technique().diagnostic_images();
}

ParamSet resolved_params(const TechniqueDescriptor& descriptor, const RawParams& given, int width, int height) {
  const FrameContent content{width, height, 0, 0};
  return resolve_params(descriptor, {gl_context().device(), {}, content, given});
}

TechniqueRenderer::TechniqueRenderer(const TechniqueDescriptor& descriptor, int width, int height)
    : technique(descriptor.create(resolved_params(descriptor, {}, width, height))),
      width(width),
      height(height),
      target(width, height) {
  technique->resize(width, height);
}

Image TechniqueRenderer::render(const SceneGpu& gpu, const glm::mat4& view, const glm::mat4& projection,
                                glm::vec3 background, bool scene_rect, ScreenRect* used) {
  const Frame frame{gpu, view, projection, width, height, background, target.framebuffer.id(), clock};
  const ScreenRect rect = render_frame(*technique, frame, false, scene_rect);
  if (used) *used = rect;
  return read_texture_rgba32f(target.color.id(), width, height);
}

Image TechniqueRenderer::render(const SceneGpu& gpu) {
  const Camera& camera = gpu.scene().camera;
  return render(gpu, camera.view, camera.projection(float(width) / float(height)), glm::vec3(0.0f), true);
}

const DiagnosticImage* find_diagnostic(const std::vector<DiagnosticImage>& images, const std::string& name) {
  for (const DiagnosticImage& d : images)
    if (d.name == name) return &d;
  ADD_FAILURE() << "no diagnostic image '" << name << "'";
  return nullptr;
}

}  // namespace oit::test
