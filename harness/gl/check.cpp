#include "harness/gl/check.h"

#include <cstdio>
#include <sstream>

#include "harness/gl/gl.h"

namespace oit {
namespace {
const char* error_name(GLenum error) {
  switch (error) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    default: return "unknown GL error";
  }
}

void GLAPIENTRY print_debug_message(GLenum, GLenum type, GLuint, GLenum severity, GLsizei,
                                   const GLchar* message, const void*) {
  // Notifications are chatty on every driver; only real problems are shown.
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  std::fprintf(stderr, "[gl debug%s] %s\n", type == GL_DEBUG_TYPE_ERROR ? " error" : "", message);
}
}  // namespace

void gl_check(const std::string& what, std::source_location where) {
  GLenum first = glGetError();
  if (first == GL_NO_ERROR) return;
  std::ostringstream msg;
  msg << error_name(first);
  // Drain the queue so one failure does not poison the next check.
  for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) msg << ", " << error_name(e);
  msg << " during " << what << " (" << where.file_name() << ":" << where.line() << ")";
  throw GlError(msg.str());
}

void drain_gl_errors() {
  while (glGetError() != GL_NO_ERROR) {
  }
}

void enable_gl_debug_output() {
  if (!epoxy_has_gl_extension("GL_KHR_debug") && epoxy_gl_version() < 43) return;
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(print_debug_message, nullptr);
}

}  // namespace oit
