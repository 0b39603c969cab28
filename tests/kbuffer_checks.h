#pragma once
// Checks both k-buffers (kbuffer, bucketed_kbuffer) must pass alike with
// k=auto; each test file states only what differs: its bytes and its bound.
#include <gtest/gtest.h>

#include <cstdint>

#include "tests/gl_fixture.h"

namespace oit::test {

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
