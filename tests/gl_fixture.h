#pragma once
// One headless GL context and harness per test process, created on first use.
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/run/runner.h"

namespace oit::test {

GlContext& gl_context();
Harness& harness();

// A run of one frame without warm-up, `size` x `size`, in `order`.
RunSpec one_frame(const std::string& technique, const RawParams& params, const std::string& scene,
                  const RawParams& scene_params, int size, const std::string& order = "original");

// one_frame() of the technique a test file is about, so the file names it
// once: `const test::OneFrameOf spec_of{"kbuffer"};` then
// spec_of(params, scene, scene_params, size[, order]), or without the size
// when `size` is given here.
struct OneFrameOf {
  std::string technique;
  int size = 0;
  RunSpec operator()(const RawParams& params, const std::string& scene, const RawParams& scene_params, int frame_size,
                     const std::string& order = "original") const {
    return one_frame(technique, params, scene, scene_params, frame_size, order);
  }
  RunSpec operator()(const RawParams& params, const std::string& scene, const RawParams& scene_params,
                     const std::string& order = "original") const {
    return one_frame(technique, params, scene, scene_params, size, order);
  }
};

// Runs `spec`, which must end `ok` and compared with the reference.
RunResult run_ok(const RunSpec& spec);

// The figure called `name` among a run's extra counters or its work_saved;
// NaN, and a test failure, when there is none.
double extra_counter(const RunResult& r, const std::string& name);
double work_saved(const RunResult& r, const std::string& name);

// The largest difference between two images' channel values.
double max_abs_difference(const Image& a, const Image& b);

// Writes `bytes` to <build>/test_output/<folder>/<name> (replacing it);
// returns the path.
std::string write_test_file(const std::string& folder, const std::string& name, const std::string& bytes);

// Writes <build>/test_output/<folder>/<name>.gltf (and .bin): full-screen
// unlit quads (view-space z, colour) in this order, seen by an orthographic
// camera looking down -z with near plane `znear`. Quads with the same z have
// identical vertices, so their fragments tie exactly in depth. Returns the path.
std::string write_quads_gltf(const std::string& folder, const std::string& name,
                             const std::vector<std::pair<float, glm::vec4>>& quads, double znear = 0.1);

// Writes <build>/test_output/<folder>/<name>.gltf: `gltf` (everything but
// the geometry's data) with the accessors, buffer views and buffer of one
// indexed mesh added: accessor 0 the VEC3 float `positions` (min and max
// computed), accessor 1 the `indices` as `index_type` (5121 unsigned byte,
// 5123 unsigned short, 5125 unsigned int), both in <name>.bin. Returns the path.
std::string write_mesh_gltf(const std::string& folder, const std::string& name, nlohmann::json gltf,
                            const std::vector<float>& positions, const std::vector<uint32_t>& indices, int index_type);

// Runs one technique with a single untimed-warm-up frame and asserts that
// the run did not error or skip.
RunResult render_once(const std::string& technique, const RawParams& params, const std::string& scene,
                      const RawParams& scene_params, int width, int height);

// Renders one frame of a technique (the scene's default camera, black
// background) and returns its diagnostic_images() of that frame.
std::vector<DiagnosticImage> diagnostic_images_once(const std::string& technique, const RawParams& params,
                                                    const std::string& scene, const RawParams& scene_params,
                                                    int width, int height);
// The RGBA that a full-screen draw of `program` (no inputs) writes at texel
// (2, 2) of a 4x4 RGBA32F target: what the shader-loader tests check.
glm::vec4 drawn_texel(const Program& program);

// One instance of a technique with default parameters, sized width x height,
// rendering frames into its own RGBA32F target (render_frame, as the
// harness does) and reading each image back.
// The parameters `given` as the harness resolves them on this device (the
// descriptor's resolution rule, for an empty frame of width x height): what a
// technique built outside Harness::run takes.
ParamSet resolved_params(const TechniqueDescriptor& descriptor, const RawParams& given, int width, int height);

struct TechniqueRenderer {
  std::unique_ptr<Technique> technique;
  int width, height;
  RenderTarget target;
  StageClock clock{ClockKind::wall};
  TechniqueRenderer(const TechniqueDescriptor& descriptor, int width, int height);
  Image render(const SceneGpu& gpu, const glm::mat4& view, const glm::mat4& projection, glm::vec3 background,
               bool scene_rect, ScreenRect* used = nullptr);
  // The scene's own camera, black background, the scene rectangle on.
  Image render(const SceneGpu& gpu);
};

// The image called `name` among `images`; nullptr, and a test failure, when there is none.
const DiagnosticImage* find_diagnostic(const std::vector<DiagnosticImage>& images, const std::string& name);

}  // namespace oit::test
