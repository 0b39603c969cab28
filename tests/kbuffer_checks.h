#pragma once
// Checks both k-buffers (kbuffer, bucketed_kbuffer) must pass alike with
// k=auto, and the RGBA8 packing bound of their images; each test file states
// only what differs: its bytes and its bound.
#include <gtest/gtest.h>

#include <cstdint>

#include "tests/gl_fixture.h"

namespace oit::test {

// Largest change of a composite (rgb and alpha) when each layer's colour and
// alpha are rounded to RGBA8, i.e. each is off by at most d = 0.5/255:
//   out = sum_i T_i a_i c_i + T_n bg,  T_i = prod_{j<i} (1 - a_j)
//   |d out / d c_i| = T_i a_i           (these sum to at most 1)
//   |d out / d a_i| = T_i |c_i - R_i|  <= T_i  (R_i: composite behind i, in [0, 1])
//   |d (1 - T_n) / d a_i| = T_n / (1 - a_i) <= T_i
// Along the segment between exact and stored values each a_j may be up to d
// smaller, so bound = d * (1 + sum_i prod_{j<i} (1 - a + d)), plus float
// rounding of the compose.
inline double packing_bound(double alpha, int layers) {
  const double d = 0.5 / 255.0;
  double transmittance_sum = 0.0, transmittance = 1.0;
  for (int i = 0; i < layers; ++i) {
    transmittance_sum += transmittance;
    transmittance *= 1.0 - alpha + d;
  }
  return d * (1.0 + transmittance_sum) + 1e-5;
}

// k=auto against the worst case k=64, both on the 32-layer quads of `pixels`
// pixels: the counting pass sized k to the 32 layers, every fragment is
// stored in count + fill + store passes, each run allocates `slot_bytes` per
// slot and `fixed_bytes` besides (auto 4 bytes of count per pixel more),
// and auto reports the memory and the slot clears it saved.
inline void expect_auto_k_on_thirty_two_layers(const RunResult& automatic, const RunResult& worst_case,
                                               uint64_t pixels, uint64_t slot_bytes, uint64_t fixed_bytes) {
  EXPECT_EQ(extra_counter(automatic, "k_used"), 32.0);
  EXPECT_EQ(extra_counter(automatic, "longest_list"), 32.0);
  EXPECT_EQ(extra_counter(automatic, "k_capped"), 0.0);
  EXPECT_EQ(automatic.counters.fragments_stored, 32u * pixels);
  EXPECT_EQ(automatic.counters.fragments_dropped, 0u);
  EXPECT_EQ(automatic.counters.passes, 3u);  // count + fill + store
  EXPECT_NE(automatic.stage("count", "wall"), nullptr);
  EXPECT_EQ(automatic.counters.bytes_allocated, pixels * 32u * slot_bytes + fixed_bytes + pixels * 4u);
  EXPECT_EQ(worst_case.counters.bytes_allocated, pixels * 64u * slot_bytes + fixed_bytes);
  EXPECT_EQ(work_saved(automatic, "bytes_not_allocated"),
            double(worst_case.counters.bytes_allocated) - double(automatic.counters.bytes_allocated));
  EXPECT_EQ(work_saved(automatic, "slots_not_cleared"), double(32u * pixels));
  // Only the harness's own figure (the scene rectangle) remains: nothing of the technique adapts with a fixed k.
  for (const auto& [name, value, combine] : worst_case.counters.work_saved)
    EXPECT_EQ(name, "pixels_outside_scene_rect");
}

}  // namespace oit::test
