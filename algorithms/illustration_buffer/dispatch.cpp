#include "algorithms/illustration_buffer/dispatch.h"

#include <algorithm>

#include "algorithms/illustration_buffer/bindings.h"

namespace oit::illustration_buffer {

void dispatch_in_groups_of_64(uint64_t invocations) {
  const uint64_t groups = (invocations + 63) / 64;
  if (groups > 0) {
    const uint64_t x = std::min<uint64_t>(groups, 65535);
    glDispatchCompute(GLuint(x), GLuint((groups + x - 1) / x), 1);
  }
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void Grid::per_fragment(GLuint program) const {
  glUseProgram(program);
  dispatch_in_groups_of_64(fragments);
}

void Grid::per_covered_pixel() const {
  if (!listed) return per_pixel();
  glBindTextureUnit(IB_LISTED_PIXELS_UNIT, covered_view);
  dispatch_in_groups_of_64(covered);
}

void Grid::per_pixel() const {
  glDispatchCompute(GLuint(width + 7) / 8, GLuint(height + 7) / 8, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

}  // namespace oit::illustration_buffer
