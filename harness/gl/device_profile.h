#pragma once
// What this program knows about the device it renders on, probed once when
// the context is made (GlContext::device()). It is the one place where
// devices differ: the techniques' resolution rules (TechniqueDescriptor::
// resolve) receive it and turn every `auto` into a concrete value before a
// technique exists, `list` and `doctor` print it, and the harness takes the
// clock it trusts from it. Nothing under algorithms/ asks the device itself.
#include <cstdint>
#include <string>
#include <vector>

namespace oit {

struct DeviceProfile {
  std::string renderer;   // GL_RENDERER
  std::string vendor;     // GL_VENDOR
  std::string version;    // GL_VERSION (includes the driver version on Mesa)
  std::string platform;   // "egl-device", "egl-surfaceless", "glfw"
  // llvmpipe, softpipe, swrast, SwiftShader: the "GPU" is the CPU.
  bool software = false;

  // Limits.
  int64_t max_storage_block_bytes = 0;    // GL_MAX_SHADER_STORAGE_BLOCK_SIZE
  int64_t max_texture_buffer_texels = 0;  // GL_MAX_TEXTURE_BUFFER_SIZE
  int max_texture_size = 0;               // GL_MAX_TEXTURE_SIZE
  int max_compute_invocations = 0;        // GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS
  uint64_t video_memory_bytes = 0;        // total, where the driver says (NVX/ATI); 0 unknown

  // Features.
  bool fp64 = false;               // double precision in shaders (GL 4.0, GL_ARB_gpu_shader_fp64)
  bool int64 = false;              // GL_ARB_gpu_shader_int64
  std::string interlock;           // ordered per-pixel access extension, "" for the spin-lock fallback
  bool framebuffer_fetch = false;  // GL_EXT_shader_framebuffer_fetch
  bool subgroup_ballot = false;    // GL_ARB_shader_ballot (subgroup-aggregated atomics)
  bool subgroup_operations = false;  // GL_KHR_shader_subgroup
  std::vector<int> msaa_sample_counts;  // of GL_RGBA8 renderbuffers, ascending

  // The clock whose stage times mean something here: "wall" (glFinish and
  // the steady clock; software GL, whose timer queries are wrong) or "gl"
  // (GL_TIMESTAMP queries: the GPU's own time, without the CPU's).
  std::string trusted_clock = "gl";
  // The harness's defaults that depend on the device: the benchmark size
  // where the work, not the fixed cost of a frame, dominates (--size auto),
  // and the least warm-up time (a GPU's clocks ramp up from idle; a software
  // rasterizer has no such ramp).
  std::string default_size = "1920x1080";
  double default_warmup_ms = 500.0;

  // One line per fact, for `list` and `doctor`.
  std::vector<std::string> describe() const;
};

// Probes the current context. `platform` says how it was made.
DeviceProfile probe_current_device(const std::string& platform);

}  // namespace oit
