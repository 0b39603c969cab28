#pragma once
#include <string>

#include "harness/gl/context.h"

struct GLFWwindow;

namespace oit {

// A window with a current GL 4.5 core context (for interactive use). The
// headless EGL path is what benchmarks and tests use.
class GlfwWindowContext final : public GlContext {
 public:
  GlfwWindowContext(int width, int height, const std::string& title);
  ~GlfwWindowContext() override;
  GlfwWindowContext(const GlfwWindowContext&) = delete;
  GlfwWindowContext& operator=(const GlfwWindowContext&) = delete;

  const DeviceProfile& device() const override { return info_; }
  GLFWwindow* window() const { return window_; }
  bool should_close() const;
  void swap_buffers_and_poll();

 private:
  GLFWwindow* window_ = nullptr;
  DeviceProfile info_;
};

}  // namespace oit
