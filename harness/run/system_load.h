#pragma once
#include <cstdint>

namespace oit {

// Measures how busy the machine was with OTHER processes between start()
// and stop(): (all busy CPU time - this process's CPU time) / (wall * cores).
// On a shared machine a high value marks a run as noisy.
class OtherProcessLoad {
 public:
  void start();
  // Fraction of all cores used by other processes, in [0, 1]; -1 if /proc is unreadable.
  double stop() const;

 private:
  struct Sample {
    uint64_t busy_ticks = 0, self_ticks = 0, total_ticks = 0;
    bool valid = false;
  };
  static Sample sample();
  Sample begin_;
};

constexpr double kNoisyLoadThreshold = 0.25;

}  // namespace oit
