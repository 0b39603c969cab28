#include "gl/context.h"

#include <epoxy/egl.h>

#include <cstring>
#include <stdexcept>
#include <vector>

#include "gl/check.h"
#include "gl/gl.h"

namespace oit {
namespace {

std::string gl_string(GLenum name) {
  const auto* text = reinterpret_cast<const char*>(glGetString(name));
  return text ? text : "";
}

bool contains(const std::string& haystack, const char* needle) { return haystack.find(needle) != std::string::npos; }

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
    info_ = query_current_device(platform);
    if (debug) enable_gl_debug_output();
  }
  ~EglContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
  const DeviceInfo& device() const override { return info_; }

 private:
  EGLDisplay display_;
  EGLContext context_ = EGL_NO_CONTEXT;
  DeviceInfo info_;
};

// Hardware EGL devices (EGL_EXT_device_enumeration), skipping Mesa's
// software device so that a GPU is preferred whenever one is present.
std::vector<EGLDeviceEXT> hardware_devices() {
  std::vector<EGLDeviceEXT> result;
  const char* client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!client_extensions || !std::strstr(client_extensions, "EGL_EXT_device_enumeration")) return result;
  EGLint count = 0;
  if (!eglQueryDevicesEXT(0, nullptr, &count) || count <= 0) return result;
  std::vector<EGLDeviceEXT> devices(static_cast<size_t>(count));
  eglQueryDevicesEXT(count, devices.data(), &count);
  for (EGLDeviceEXT device : devices) {
    const char* extensions = eglQueryDeviceStringEXT(device, EGL_EXTENSIONS);
    if (extensions && std::strstr(extensions, "EGL_MESA_device_software")) continue;
    result.push_back(device);
  }
  return result;
}

}  // namespace

DevicePreference parse_device_preference(const std::string& text) {
  if (text == "auto") return DevicePreference::automatic;
  if (text == "gpu") return DevicePreference::gpu;
  if (text == "software") return DevicePreference::software;
  throw std::invalid_argument("device '" + text + "' is not one of auto, gpu, software");
}

DeviceInfo query_current_device(const std::string& platform) {
  DeviceInfo info;
  info.renderer = gl_string(GL_RENDERER);
  info.vendor = gl_string(GL_VENDOR);
  info.version = gl_string(GL_VERSION);
  info.platform = platform;
  info.software = contains(info.renderer, "llvmpipe") || contains(info.renderer, "softpipe") ||
                  contains(info.renderer, "swrast") || contains(info.renderer, "SwiftShader");
  info.has_fp64 = epoxy_has_gl_extension("GL_ARB_gpu_shader_fp64") || epoxy_gl_version() >= 40;
  info.has_int64 = epoxy_has_gl_extension("GL_ARB_gpu_shader_int64");
  if (epoxy_gl_version() < 45) {
    throw std::runtime_error("OpenGL 4.5 is required, the context on " + platform + " offers " + info.version +
                             " (" + info.renderer + ")");
  }
  return info;
}

std::unique_ptr<GlContext> create_headless_context(DevicePreference preference, bool debug) {
  std::string tried;
  if (preference != DevicePreference::software) {
    for (EGLDeviceEXT device : hardware_devices()) {
      EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
      if (display == EGL_NO_DISPLAY) continue;
      try {
        return std::make_unique<EglContext>(display, "egl-device", debug);
      } catch (const std::exception& e) {
        tried += std::string("\n  egl-device: ") + e.what();
      }
    }
    if (preference == DevicePreference::gpu) {
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
