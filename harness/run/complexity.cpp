#include "harness/run/complexity.h"

#include <algorithm>
#include <stdexcept>

#include "harness/output/heatmap.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"
#include "harness/gl/uniforms.h"
#include "shaders/bindings.h"

namespace oit {

DepthComplexity measure_depth_complexity(const SceneGpu& scene, const glm::mat4& view, const glm::mat4& projection,
                                         int width, int height) {
  // Built per call, not kept in a static: a static program would outlive the
  // context and be deleted at exit without one. Callers measure once per
  // scene and size, and Mesa's shader cache makes the rebuild cheap.
  const Program program = build_geometry_program("shaders/count_fragments.frag");
  Texture counts = make_texture_2d(GL_R32UI, width, height);
  const GLuint zero = 0;
  glClearTexImage(counts.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  Framebuffer framebuffer = make_framebuffer();
  glNamedFramebufferParameteri(framebuffer.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, width);
  glNamedFramebufferParameteri(framebuffer.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, height);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glUseProgram(program.id());
  set_uniform(program.id(), OIT_UNIFORM_VIEW, view);
  set_uniform(program.id(), OIT_UNIFORM_PROJECTION, projection);
  glBindImageTexture(0, counts.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  scene.draw();
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);

  DepthComplexity result;
  result.width = width;
  result.height = height;
  result.per_pixel.resize(size_t(width) * size_t(height));
  glGetTextureImage(counts.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(result.per_pixel.size() * 4),
                    result.per_pixel.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  // The program is deleted on return: leaving it in use would leave a name
  // that code saving and restoring GL_CURRENT_PROGRAM (ImGui's renderer in
  // `oitbench view`) restores after the name is gone (GL_INVALID_VALUE).
  glUseProgram(0);
  gl_check("depth complexity pass");
  summarize_depth_complexity(result);
  return result;
}

void summarize_depth_complexity(DepthComplexity& c) {
  c.fragments = 0;
  c.max = 0;
  c.covered_pixels = 0;
  for (uint32_t count : c.per_pixel) {
    c.fragments += count;
    c.max = std::max(c.max, count);
    c.covered_pixels += count > 0;
  }
  c.mean = c.per_pixel.empty() ? 0.0 : double(c.fragments) / double(c.per_pixel.size());
  uint64_t long_lists = 0;
  if (c.max > 0)
    for (uint32_t count : c.per_pixel) long_lists += 3ull * count > 2ull * c.max;
  c.psi = c.per_pixel.empty() ? 0.0 : double(long_lists) / double(c.per_pixel.size());
}

std::vector<uint64_t> list_length_histogram(const DepthComplexity& c) {
  std::vector<uint64_t> histogram(size_t(c.max) + 1, 0);
  for (uint32_t count : c.per_pixel) {
    if (count >= histogram.size()) histogram.resize(size_t(count) + 1, 0);  // per_pixel changed after summarizing
    ++histogram[count];
  }
  return histogram;
}

std::vector<HistogramBin> binned_histogram(const std::vector<uint64_t>& histogram, size_t max_bins) {
  std::vector<HistogramBin> bins;
  if (histogram.empty() || max_bins == 0) return bins;
  const size_t width = (histogram.size() + max_bins - 1) / max_bins;
  for (size_t first = 0; first < histogram.size(); first += width) {
    HistogramBin bin{uint32_t(first), uint32_t(std::min(first + width, histogram.size()) - 1), 0};
    for (size_t n = bin.first; n <= bin.last; ++n) bin.pixels += histogram[n];
    bins.push_back(bin);
  }
  return bins;
}

ColourScale list_length_scale(const DepthComplexity& c) {
  // An empty view is all the bottom colour over 0 .. 1.
  return {ColourScale::Kind::linear, 0.0f, c.max > 0 ? float(c.max) : 1.0f};
}

Image list_length_heatmap(const DepthComplexity& c) {
  std::vector<float> values(c.per_pixel.begin(), c.per_pixel.end());
  return heatmap(values, c.width, c.height, list_length_scale(c));
}

ChosenViewpoint choose_max_list_camera(const SceneGpu& scene, const CameraSpec& spec, int probe_size) {
  if (spec.kind != CameraSpec::Kind::max_list && spec.kind != CameraSpec::Kind::random_set)
    throw std::invalid_argument("camera '" + spec.text() + "' is not a set of viewpoints to choose from");
  const BoundingSphere sphere = scene.scene().bounds();
  ChosenViewpoint best;
  double best_mean = -1.0;
  for (uint32_t i = 0; i < spec.count; ++i) {
    const Camera camera = random_viewpoint(sphere, spec.seed, i);
    const DepthComplexity c =
        measure_depth_complexity(scene, camera.view, camera.projection(1.0f), probe_size, probe_size);
    if (i == 0 || c.max > best.max_list || (c.max == best.max_list && c.mean > best_mean)) {
      best = {i, camera, c.max};
      best_mean = c.mean;
    }
  }
  return best;
}

Camera resolve_camera(const SceneGpu& scene, const std::string& camera_spec) {
  const CameraSpec spec = parse_camera_spec(camera_spec);
  if (spec.kind == CameraSpec::Kind::max_list) return choose_max_list_camera(scene, spec).camera;
  return camera_for_spec(scene.scene(), spec);
}

}  // namespace oit
