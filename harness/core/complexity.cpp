#include "core/complexity.h"

#include <algorithm>

#include "gl/check.h"
#include "gl/shader_program.h"
#include "../../shaders/bindings.h"

namespace oit {

DepthComplexity measure_depth_complexity(const SceneGpu& scene, const glm::mat4& view, const glm::mat4& projection,
                                         int width, int height) {
  static thread_local Program program;  // compiled once per context thread
  if (!program) program = build_geometry_program("shaders/count_fragments.frag");
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
  glProgramUniformMatrix4fv(program.id(), OIT_UNIFORM_VIEW, 1, GL_FALSE, &view[0][0]);
  glProgramUniformMatrix4fv(program.id(), OIT_UNIFORM_PROJECTION, 1, GL_FALSE, &projection[0][0]);
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
  gl_check("depth complexity pass");
  for (uint32_t count : result.per_pixel) {
    result.fragments += count;
    result.max = std::max(result.max, count);
  }
  result.mean = result.per_pixel.empty() ? 0.0 : double(result.fragments) / double(result.per_pixel.size());
  return result;
}

}  // namespace oit
