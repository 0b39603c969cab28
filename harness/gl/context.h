#pragma once
#include <memory>
#include <string>
#include <vector>

#include "harness/gl/device_profile.h"

namespace oit {

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
  virtual const DeviceProfile& device() const = 0;
};

// Headless context through EGL. auto and gpu: a hardware device of the EGL
// device platform (with CUDA_VISIBLE_DEVICES set, as SLURM sets it for an
// allocated GPU, the NVIDIA device that is CUDA device 0 of this process is
// tried first), else (auto only) Mesa's surfaceless platform (llvmpipe);
// egl:N: that device or an error naming the devices there are. Throws
// std::runtime_error saying what was tried.
std::unique_ptr<GlContext> create_headless_context(const DeviceChoice& choice = {}, bool debug = false);


}  // namespace oit
