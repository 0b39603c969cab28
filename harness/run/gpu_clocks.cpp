#include "harness/run/gpu_clocks.h"

#include <dlfcn.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace oit {
namespace {

// NVML's constants (nvml.h): NVML_SUCCESS, NVML_CLOCK_SM, NVML_CLOCK_MEM,
// NVML_TEMPERATURE_GPU.
constexpr int kSuccess = 0, kClockSm = 1, kClockMemory = 2, kTemperatureGpu = 0;

template <typename F>
F symbol(void* library, const char* name) {
  return reinterpret_cast<F>(dlsym(library, name));
}

unsigned visible_cuda_device() {
  const char* visible = std::getenv("CUDA_VISIBLE_DEVICES");
  if (!visible || !*visible) return 0;
  char* end = nullptr;
  const long index = std::strtol(visible, &end, 10);
  return end != visible && index >= 0 ? unsigned(index) : 0;  // a UUID list: the first NVML device
}

}  // namespace

GpuClocks::GpuClocks() {
  const char* named = std::getenv("OIT_NVML_LIBRARY");
  const std::string path = named && *named ? named : "libnvidia-ml.so.1";
  library_ = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!library_) {
    reason_ = "NVML (" + path + ") is not installed";
    return;
  }
  auto init = symbol<int (*)()>(library_, "nvmlInit_v2");
  auto by_index = symbol<int (*)(unsigned, void**)>(library_, "nvmlDeviceGetHandleByIndex_v2");
  clock_info_ = symbol<int (*)(void*, int, unsigned*)>(library_, "nvmlDeviceGetClockInfo");
  temperature_ = symbol<int (*)(void*, int, unsigned*)>(library_, "nvmlDeviceGetTemperature");
  shutdown_ = symbol<int (*)()>(library_, "nvmlShutdown");
  if (!init || !by_index || !clock_info_ || !temperature_ || !shutdown_) {
    reason_ = path + " lacks the NVML functions read here";
    return;
  }
  if (init() != kSuccess) {
    reason_ = "nvmlInit failed (no NVIDIA driver running?)";
    shutdown_ = nullptr;
    return;
  }
  if (by_index(visible_cuda_device(), &device_) != kSuccess) {
    device_ = nullptr;
    reason_ = "NVML has no device " + std::to_string(visible_cuda_device());
  }
}

GpuClocks::~GpuClocks() {
  if (shutdown_) shutdown_();
  if (library_) dlclose(library_);
}

std::optional<GpuClockReading> GpuClocks::read() const {
  if (!device_) return std::nullopt;
  GpuClockReading reading;
  if (clock_info_(device_, kClockSm, &reading.sm_mhz) != kSuccess ||
      clock_info_(device_, kClockMemory, &reading.memory_mhz) != kSuccess ||
      temperature_(device_, kTemperatureGpu, &reading.temperature_c) != kSuccess)
    return std::nullopt;
  return reading;
}

std::string clock_moved_warning(const GpuClockReading& start, const GpuClockReading& end) {
  if (start.sm_mhz == 0) return "";
  const double change = (double(end.sm_mhz) - double(start.sm_mhz)) / double(start.sm_mhz);
  if (std::abs(change) <= 0.10) return "";
  char text[128];
  std::snprintf(text, sizeof text, "the SM clock moved from %u to %u MHz during the run (%+.0f%%)", start.sm_mhz,
                end.sm_mhz, change * 100.0);
  return text;
}

}  // namespace oit
