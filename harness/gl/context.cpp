#include "harness/gl/context.h"

#include <epoxy/egl.h>

#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "harness/gl/check.h"
#include "harness/gl/gl.h"

namespace oit {
namespace {


class EglContext final : public GlContext {
 public:
  EglContext(EGLDisplay display, const std::string& platform, bool debug) : display_(display) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display_, &major, &minor)) throw std::runtime_error("eglInitialize failed on " + platform);
    if (!eglBindAPI(EGL_OPENGL_API)) throw std::runtime_error("eglBindAPI(EGL_OPENGL_API) failed on " + platform);
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                 EGL_CONTEXT_OPENGL_DEBUG, debug ? EGL_TRUE : EGL_FALSE, EGL_NONE};
    // No config and no surface: rendering goes to framebuffer objects only.
    context_ = eglCreateContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (context_ == EGL_NO_CONTEXT) {
      eglTerminate(display_);
      throw std::runtime_error("could not create an OpenGL 4.5 core context on " + platform);
    }
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
      eglDestroyContext(display_, context_);
      eglTerminate(display_);
      throw std::runtime_error("eglMakeCurrent failed on " + platform);
    }
    info_ = probe_current_device(platform);
    if (debug) enable_gl_debug_output();
  }
  ~EglContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
  const DeviceProfile& device() const override { return info_; }

 private:
  EGLDisplay display_;
  EGLContext context_ = EGL_NO_CONTEXT;
  DeviceProfile info_;
};

// An EGL device (EGL_EXT_device_enumeration) and what its extensions say about it.
struct EglDevice {
  EGLDeviceEXT handle = nullptr;
  bool software = false;   // EGL_MESA_device_software (llvmpipe)
  std::string drm_file;    // EGL_EXT_device_drm: /dev/dri/cardN
  int cuda_device = -1;    // EGL_NV_device_cuda: this process's CUDA ordinal (CUDA_VISIBLE_DEVICES applies)
};

bool has_extension(const char* extensions, const char* name) {
  return extensions && std::strstr(extensions, name) != nullptr;
}

// Every EGL device in the driver's order: the numbering of --device egl:N.
std::vector<EglDevice> egl_devices() {
  std::vector<EglDevice> result;
  if (!has_extension(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS), "EGL_EXT_device_enumeration")) return result;
  EGLint count = 0;
  if (!eglQueryDevicesEXT(0, nullptr, &count) || count <= 0) return result;
  std::vector<EGLDeviceEXT> handles(static_cast<size_t>(count));
  if (!eglQueryDevicesEXT(count, handles.data(), &count)) return result;
  handles.resize(static_cast<size_t>(count));
  for (EGLDeviceEXT handle : handles) {
    EglDevice device;
    device.handle = handle;
    const char* extensions = eglQueryDeviceStringEXT(handle, EGL_EXTENSIONS);
    device.software = has_extension(extensions, "EGL_MESA_device_software");
    if (has_extension(extensions, "EGL_EXT_device_drm")) {
      const char* file = eglQueryDeviceStringEXT(handle, EGL_DRM_DEVICE_FILE_EXT);
      if (file) device.drm_file = file;
    }
    EGLAttrib cuda = -1;
    if (has_extension(extensions, "EGL_NV_device_cuda") && eglQueryDeviceAttribEXT(handle, EGL_CUDA_DEVICE_NV, &cuda))
      device.cuda_device = static_cast<int>(cuda);
    result.push_back(device);
  }
  return result;
}

std::string describe(const EglDevice& device, size_t index) {
  std::string text = "egl:" + std::to_string(index);
  if (device.software) text += " software (Mesa)";
  if (!device.drm_file.empty()) text += " " + device.drm_file;
  if (device.cuda_device >= 0) text += " CUDA device " + std::to_string(device.cuda_device);
  if (!device.software && device.drm_file.empty() && device.cuda_device < 0) text += " hardware";
  return text;
}

std::unique_ptr<GlContext> open_device(const EglDevice& device, bool debug) {
  EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device.handle, nullptr);
  if (display == EGL_NO_DISPLAY) throw std::runtime_error("eglGetPlatformDisplayEXT gave no display");
  return std::make_unique<EglContext>(display, "egl-device", debug);
}

std::unique_ptr<GlContext> open_indexed_device(int index, bool debug) {
  const std::vector<EglDevice> devices = egl_devices();
  std::string listing;
  for (size_t i = 0; i < devices.size(); ++i) listing += "\n  " + describe(devices[i], i);
  if (index < 0 || static_cast<size_t>(index) >= devices.size()) {
    throw std::runtime_error("--device egl:" + std::to_string(index) + ": this machine has " +
                             std::to_string(devices.size()) + " EGL device(s)" +
                             (devices.empty() ? " (no EGL_EXT_device_enumeration)" : ":" + listing));
  }
  try {
    return open_device(devices[static_cast<size_t>(index)], debug);
  } catch (const std::exception& e) {
    throw std::runtime_error("--device " + describe(devices[static_cast<size_t>(index)], static_cast<size_t>(index)) +
                             ": " + e.what());
  }
}

// A GPU that SLURM (or the user) handed this process through
// CUDA_VISIBLE_DEVICES is CUDA device 0 here; NVIDIA's EGL says which EGL
// device that is. Other GPUs may belong to other jobs: never fall back to them.
const EglDevice* allocated_cuda_device(const std::vector<EglDevice>& hardware) {
  const char* visible = std::getenv("CUDA_VISIBLE_DEVICES");
  if (!visible || !*visible) return nullptr;
  for (const EglDevice& device : hardware)
    if (device.cuda_device == 0) return &device;
  return nullptr;
}

}  // namespace

DeviceChoice parse_device_choice(const std::string& text) {
  if (text == "auto") return {DevicePreference::automatic};
  if (text == "gpu") return {DevicePreference::gpu};
  if (text == "software") return {DevicePreference::software};
  if (text.rfind("egl:", 0) == 0) {
    const std::string digits = text.substr(4);
    if (!digits.empty() && digits.size() <= 4 && digits.find_first_not_of("0123456789") == std::string::npos)
      return {DevicePreference::egl_index, std::stoi(digits)};
  }
  throw std::invalid_argument("device '" + text + "' is not one of auto, gpu, software, egl:N (N = 0, 1, ...)");
}

std::vector<std::string> describe_egl_devices() {
  const std::vector<EglDevice> devices = egl_devices();
  std::vector<std::string> lines;
  for (size_t i = 0; i < devices.size(); ++i) lines.push_back(describe(devices[i], i));
  return lines;
}


std::unique_ptr<GlContext> create_headless_context(const DeviceChoice& choice, bool debug) {
  if (choice.preference == DevicePreference::egl_index) return open_indexed_device(choice.egl_index, debug);
  std::string tried;
  if (choice.preference != DevicePreference::software) {
    std::vector<EglDevice> hardware = egl_devices();
    std::erase_if(hardware, [](const EglDevice& d) { return d.software; });
    if (const EglDevice* allocated = allocated_cuda_device(hardware)) {
      try {
        return open_device(*allocated, debug);
      } catch (const std::exception& e) {
        throw std::runtime_error(std::string("the GPU of CUDA_VISIBLE_DEVICES (CUDA device 0) could not be used: ") +
                                 e.what());
      }
    }
    // A job given a GPU must not time another one, nor llvmpipe, unnoticed.
    if (const char* visible = std::getenv("CUDA_VISIBLE_DEVICES"); visible && *visible) {
      throw std::runtime_error(std::string("CUDA_VISIBLE_DEVICES=") + visible +
                               " but no EGL device is its GPU (CUDA device 0; NVIDIA's EGL driver reports it): "
                               "give --device software to render on the CPU, --device egl:N for a device `oitbench "
                               "--device software list` shows, or unset CUDA_VISIBLE_DEVICES");
    }
    for (const EglDevice& device : hardware) {
      try {
        return open_device(device, debug);
      } catch (const std::exception& e) {
        tried += std::string("\n  egl-device: ") + e.what();
      }
    }
    if (choice.preference == DevicePreference::gpu) {
      throw std::runtime_error("no hardware EGL device could be used (--device gpu)" + tried);
    }
  }
  EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY) {
    throw std::runtime_error("no EGL display: neither a GPU device nor Mesa's surfaceless platform is available "
                             "(install libegl-mesa0 and libgl1-mesa-dri)" + tried);
  }
  return std::make_unique<EglContext>(display, "egl-surfaceless", debug);
}

}  // namespace oit
