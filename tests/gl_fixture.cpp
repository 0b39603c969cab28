#include "tests/gl_fixture.h"

#include <gtest/gtest.h>

#include "harness/core/image.h"
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

RunResult render_once(const std::string& technique, const RawParams& params, const std::string& scene,
                      const RawParams& scene_params, int width, int height) {
  RunSpec spec;
  spec.technique = technique;
  spec.params = params;
  spec.scene = scene;
  spec.scene_params = scene_params;
  spec.width = width;
  spec.height = height;
  spec.warmup = 0;
  spec.frames = 1;
  RunResult result = harness().run(spec);
  EXPECT_EQ(result.status, RunStatus::ok) << technique << ": " << result.message;
  return result;
}

std::vector<DiagnosticImage> diagnostic_images_once(const std::string& technique, const RawParams& params,
                                                    const std::string& scene, const RawParams& scene_params,
                                                    int width, int height) {
  gl_context();
  const TechniqueDescriptor& descriptor = builtin_techniques().get(technique);
  const ParamSet values(descriptor.params, params, technique);
  const Scene loaded = load_scene(scene, scene_params);
  const SceneGpu gpu(loaded);
  const Camera camera = resolve_camera(gpu, "default");
  std::unique_ptr<Technique> instance = descriptor.create(values);
  instance->resize(width, height);
  RenderTarget target(width, height);
  StageClock clock(ClockKind::wall);
  const Frame frame{gpu, camera.view, camera.projection(float(width) / float(height)), width, height,
                    glm::vec3(0.0f), target.framebuffer.id(), clock};
  render_frame(*instance, frame, false);
  return instance->diagnostic_images();
}

const DiagnosticImage* find_diagnostic(const std::vector<DiagnosticImage>& images, const std::string& name) {
  for (const DiagnosticImage& d : images)
    if (d.name == name) return &d;
  ADD_FAILURE() << "no diagnostic image '" << name << "'";
  return nullptr;
}

}  // namespace oit::test
