#pragma once
// The GPU's clocks and temperature, read through NVIDIA's NVML where the
// driver installs it (libnvidia-ml.so.1, opened with dlopen: nothing to
// install, nothing changed on the device: no clock is locked). Elsewhere,
// and on software GL, nothing is read and the CSV's clock columns stay empty.
#include <optional>
#include <string>

namespace oit {

// The clocks of the GPU at one moment: a run's start (right after its
// warm-up) or end (right after its last timed frame), both read while the
// GPU is still under the run's load (RunResult).
struct GpuClockReading {
  unsigned sm_mhz = 0, memory_mhz = 0, temperature_c = 0;
};

class GpuClocks {
 public:
  // Opens NVML (OIT_NVML_LIBRARY names another library, for tests) and the
  // GPU this process renders on: CUDA device 0 of CUDA_VISIBLE_DEVICES, else
  // NVML's device 0. Unavailable when the library or the device is missing.
  GpuClocks();
  ~GpuClocks();
  GpuClocks(const GpuClocks&) = delete;
  GpuClocks& operator=(const GpuClocks&) = delete;

  bool available() const { return device_ != nullptr; }
  // The SM and memory clocks and the temperature now; nullopt when unavailable.
  std::optional<GpuClockReading> read() const;
  // Why the clocks are not read ("" when they are).
  const std::string& unavailable_reason() const { return reason_; }

 private:
  void* library_ = nullptr;
  void* device_ = nullptr;
  int (*clock_info_)(void*, int, unsigned*) = nullptr;
  int (*temperature_)(void*, int, unsigned*) = nullptr;
  int (*shutdown_)() = nullptr;
  std::string reason_;
};

// The warning when the SM clock moved by more than 10% between a run's
// start and end, "" otherwise.
std::string clock_moved_warning(const GpuClockReading& start, const GpuClockReading& end);

}  // namespace oit
