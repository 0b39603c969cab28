#pragma once
#include <memory>
#include <string>

namespace oit {

// What a result must record about the device it ran on.
struct DeviceInfo {
  std::string renderer;   // GL_RENDERER
  std::string vendor;     // GL_VENDOR
  std::string version;    // GL_VERSION (includes the driver version on Mesa)
  std::string platform;   // "egl-device", "egl-surfaceless", "glfw"
  bool software = false;  // llvmpipe/softpipe/swrast: GL timer queries are unreliable
  bool has_fp64 = false;  // GL_ARB_gpu_shader_fp64
  bool has_int64 = false; // GL_ARB_gpu_shader_int64
};

enum class DevicePreference { automatic, gpu, software };
DevicePreference parse_device_preference(const std::string& text);

// A current OpenGL 4.5 core context. Destroying it releases the context.
class GlContext {
 public:
  virtual ~GlContext() = default;
  virtual const DeviceInfo& device() const = 0;
};

// Headless context through EGL: a hardware device of the EGL device platform
// when one exists (and `preference` allows), otherwise Mesa's surfaceless
// platform (llvmpipe). Throws std::runtime_error saying what was tried.
std::unique_ptr<GlContext> create_headless_context(DevicePreference preference = DevicePreference::automatic,
                                                   bool debug = false);


DeviceInfo query_current_device(const std::string& platform);

}  // namespace oit
