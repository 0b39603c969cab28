#pragma once
// A cheap counting pass for techniques that size per-pixel storage from the
// view they are about to render (k=auto): one geometry pass with no depth
// test counts every pixel's fragments; the longest list of the frame sizes
// the storage. Technique-independent; the technique times it (stage `count`).
#include <cstdint>
#include <vector>

#include "harness/core/technique.h"
#include "harness/gl/handles.h"

namespace oit {

class ListLengthPass {
 public:
  ListLengthPass();
  // The per-pixel count target for this size.
  void resize(int width, int height);
  // Draws frame.scene with the frame's camera and returns the longest
  // per-pixel fragment list (0 for an empty view). Reads the counts back,
  // so it waits for the pass: the caller needs the number before going on.
  // Leaves another framebuffer and program bound.
  uint32_t longest_list(const Frame& frame);
  // The fragments that pass counted, summed from the same read-back (exact:
  // every count is a whole number below 2^24).
  uint64_t total_fragments() const { return total_; }
  // The R32F count target (4 bytes per pixel).
  uint64_t bytes_allocated() const;
  // That target, holding the last pass's per-pixel counts (e.g. for a prefix sum).
  const Texture& counts() const { return counts_; }

 private:
  Program program_;
  Texture counts_;
  Framebuffer framebuffer_;
  std::vector<float> readback_;
  int width_ = 0, height_ = 0;
  uint64_t total_ = 0;
};

// The most slots per pixel (at least 1, at most max_slots) that a technique
// sizing itself from ListLengthPass may allocate at width x height: all its
// per-slot arrays (bytes_per_slot in all) within memory_cap_bytes, and its
// largest single array (largest_array_bytes_per_slot) within the device's
// largest storage block.
int slots_per_pixel_cap(int width, int height, uint64_t memory_cap_bytes, uint64_t bytes_per_slot,
                        uint64_t largest_array_bytes_per_slot, int max_slots);

}  // namespace oit
