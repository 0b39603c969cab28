#pragma once
#include <memory>
#include <string>
#include <vector>

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

enum class DevicePreference { automatic, gpu, software, egl_index };

// `--device`: auto, gpu, software or egl:N (the N-th EGL device in the order
// `oitbench list` prints them, software ones included).
struct DeviceChoice {
  DevicePreference preference = DevicePreference::automatic;
  int egl_index = -1;  // with DevicePreference::egl_index
};
DeviceChoice parse_device_choice(const std::string& text);

// One line per EGL device (EGL_EXT_device_enumeration), numbered as egl:N
// takes them: DRM node, CUDA device, software. Empty without the extension.
std::vector<std::string> describe_egl_devices();

// A current OpenGL 4.5 core context. Destroying it releases the context.
class GlContext {
 public:
  virtual ~GlContext() = default;
  virtual const DeviceInfo& device() const = 0;
};

// Headless context through EGL. auto and gpu: a hardware device of the EGL
// device platform (with CUDA_VISIBLE_DEVICES set, as SLURM sets it for an
// allocated GPU, the NVIDIA device that is CUDA device 0 of this process is
// tried first), else (auto only) Mesa's surfaceless platform (llvmpipe);
// egl:N: that device or an error naming the devices there are. Throws
// std::runtime_error saying what was tried.
std::unique_ptr<GlContext> create_headless_context(const DeviceChoice& choice = {}, bool debug = false);


DeviceInfo query_current_device(const std::string& platform);

// Whether the current context renders in software (llvmpipe, softpipe,
// swrast, SwiftShader): there the "GPU" is the CPU, so a technique may pick
// the host for work a GPU would do in a shader (DeviceInfo::software).
bool current_device_is_software();

// Whether the current context has GL_EXT_shader_framebuffer_fetch: a
// fragment reads and writes its pixel's colour in primitive order, which
// lets a fill take per-pixel slots without atomics.
bool current_device_has_framebuffer_fetch();

}  // namespace oit
