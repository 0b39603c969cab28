#include "harness/toolkit/pixel_locks.h"

#include "harness/gl/check.h"
#include "harness/gl/shader_capabilities.h"

namespace oit {

void PixelLocks::resize(int width, int height) {
  bytes_ = 4 + uint64_t(width) * uint64_t(height) * 4;
  buffer_ = make_buffer(GLsizeiptr(bytes_));
  gl_check("allocating the pixel locks of " + std::to_string(width) + "x" + std::to_string(height));
}

void PixelLocks::clear() const {
  fill_buffer_u32(buffer_, 0);
}

void PixelLocks::bind(GLuint binding) const { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer_.id()); }

uint32_t PixelLocks::failures() const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  GLuint failures = 0;
  glGetNamedBufferSubData(buffer_.id(), 0, sizeof failures, &failures);
  return failures;
}

std::vector<Figure> PixelLocks::counters() const {
  return {{"lock_failures", double(failures())}, {"interlock", ordered_access_extension().empty() ? 0.0 : 1.0, Combine::max}};
}

}  // namespace oit
