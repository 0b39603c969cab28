#include "harness/gl/device_profile.h"

#include <algorithm>
#include <set>
#include <stdexcept>

#include "harness/gl/gl.h"
#include "harness/gl/shader_capabilities.h"

namespace oit {
namespace {

// GL_NVX_gpu_memory_info's dedicated video memory (KiB).
constexpr GLenum kNvxDedicatedVideoMemory = 0x9047;

std::string gl_string(GLenum name) {
  const auto* text = reinterpret_cast<const char*>(glGetString(name));
  return text ? text : "";
}

std::set<std::string> gl_extensions() {
  std::set<std::string> names;
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i)
    if (const auto* name = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)))) names.insert(name);
  return names;
}

bool is_software_renderer(const std::string& renderer) {
  for (const char* name : {"llvmpipe", "softpipe", "swrast", "SwiftShader"})
    if (renderer.find(name) != std::string::npos) return true;
  return false;
}

std::vector<int> msaa_sample_counts() {
  GLint count = 0;
  glGetInternalformativ(GL_RENDERBUFFER, GL_RGBA8, GL_NUM_SAMPLE_COUNTS, 1, &count);
  std::vector<int> samples(size_t(std::max(count, 0)));
  if (count > 0) glGetInternalformativ(GL_RENDERBUFFER, GL_RGBA8, GL_SAMPLES, count, samples.data());
  std::sort(samples.begin(), samples.end());
  return samples;
}

std::string yes_no(bool value) { return value ? "yes" : "no"; }

}  // namespace

DeviceProfile probe_current_device(const std::string& platform) {
  DeviceProfile p;
  p.renderer = gl_string(GL_RENDERER);
  p.vendor = gl_string(GL_VENDOR);
  p.version = gl_string(GL_VERSION);
  p.platform = platform;
  if (epoxy_gl_version() < 45) {
    throw std::runtime_error("OpenGL 4.5 is required, the context on " + platform + " offers " + p.version + " (" +
                             p.renderer + ")");
  }
  p.software = is_software_renderer(p.renderer);
  const std::set<std::string> extensions = gl_extensions();
  auto has = [&](const char* name) { return extensions.count(name) > 0; };
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &p.max_storage_block_bytes);
  glGetInteger64v(GL_MAX_TEXTURE_BUFFER_SIZE, &p.max_texture_buffer_texels);
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &p.max_texture_size);
  glGetIntegerv(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS, &p.max_compute_invocations);
  if (has("GL_NVX_gpu_memory_info")) {
    GLint kib = 0;
    glGetIntegerv(kNvxDedicatedVideoMemory, &kib);
    p.video_memory_bytes = kib > 0 ? uint64_t(kib) * 1024 : 0;
  }
  p.fp64 = has("GL_ARB_gpu_shader_fp64") || epoxy_gl_version() >= 40;
  p.int64 = has("GL_ARB_gpu_shader_int64");
  p.interlock = ordered_access_extension();
  p.framebuffer_fetch = has("GL_EXT_shader_framebuffer_fetch");
  p.subgroup_ballot = has("GL_ARB_shader_ballot");
  p.subgroup_operations = has("GL_KHR_shader_subgroup");
  p.msaa_sample_counts = msaa_sample_counts();
  // Mesa's software rasterizers answer timer queries, but per-pass
  // timestamps there do not bracket the work (the rasterizer runs deferred).
  p.trusted_clock = p.software ? "wall" : "gl";
  p.default_size = p.software ? "256x256" : "1920x1080";
  p.default_warmup_ms = p.software ? 0.0 : 500.0;
  return p;
}

std::vector<std::string> DeviceProfile::describe() const {
  std::string samples;
  for (int s : msaa_sample_counts) samples += (samples.empty() ? "" : ",") + std::to_string(s);
  return {
      "renderer: " + renderer + " (" + vendor + ")",
      "version: " + version + ", platform " + platform,
      "software: " + yes_no(software) + "; trusted clock: " + trusted_clock +
          (software ? " (glFinish and the steady clock: timer queries are wrong here)" : " (GL timer queries)"),
      "defaults: --size auto = " + default_size + ", least warm-up " + std::to_string(int(default_warmup_ms)) + " ms",
      "limits: storage block " + std::to_string(max_storage_block_bytes) + " B, texture buffer " +
          std::to_string(max_texture_buffer_texels) + " texels, texture " + std::to_string(max_texture_size) +
          ", compute invocations " + std::to_string(max_compute_invocations) + ", video memory " +
          (video_memory_bytes ? std::to_string(video_memory_bytes >> 20) + " MiB" : std::string("unknown")),
      "features: fp64 " + yes_no(fp64) + ", int64 " + yes_no(int64) + ", interlock " +
          (interlock.empty() ? std::string("no (spin lock)") : interlock) + ", framebuffer fetch " +
          yes_no(framebuffer_fetch) + ", subgroup ballot " + yes_no(subgroup_ballot) + ", subgroup operations " +
          yes_no(subgroup_operations) + ", MSAA samples {" + samples + "}",
  };
}

}  // namespace oit
