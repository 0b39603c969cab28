#include "harness/gl/glfw_window.h"

#include <GLFW/glfw3.h>

#include <stdexcept>

namespace oit {
namespace {
std::string last_glfw_error() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description ? description : "unknown GLFW error";
}
}  // namespace

GlfwWindowContext::GlfwWindowContext(int width, int height, const std::string& title) {
  if (!glfwInit()) {
    throw std::runtime_error("cannot open a window: " + last_glfw_error() +
                             ". Without a display use `oitbench render` / `oitbench bench`, or run under xvfb-run.");
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    std::string reason = last_glfw_error();
    glfwTerminate();
    throw std::runtime_error("cannot create a 4.5 core window: " + reason);
  }
  glfwMakeContextCurrent(window_);
  info_ = probe_current_device("glfw");
}

GlfwWindowContext::~GlfwWindowContext() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

bool GlfwWindowContext::should_close() const { return glfwWindowShouldClose(window_); }

void GlfwWindowContext::swap_buffers_and_poll() {
  glfwSwapBuffers(window_);
  glfwPollEvents();
}

}  // namespace oit
