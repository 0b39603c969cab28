#pragma once
// The fragment pool of the list-based techniques (linked_list, reference,
// illustration_buffer), in one owner: how many nodes to hold, growing with a
// re-render when a fill overflows, shrinking when far above the need, the
// device-limit check, and the history per screen tile (harness/run/tiling.h), so
// that the tiles of one frame share a pool sized for the largest of them
// instead of reallocating tile after tile. The technique owns the buffers
// (their layout is its own): the pool calls `allocate(capacity)` whenever
// the capacity changes.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "harness/toolkit/technique.h"

namespace oit {

namespace fragment_pool {

// Nodes for `fragments` plus 25% slack (+1: never an empty pool).
constexpr uint64_t capacity_for(uint64_t fragments) { return fragments + fragments / 4 + 1; }

// The capacity to shrink to when the most fragments any tile of the last
// frame produced is `previous_fragments` (none known: 0), or 0 to keep
// `capacity`: only past a factor 2, so that it does not reallocate every
// frame.
constexpr uint64_t shrunk_capacity(uint64_t capacity, uint64_t previous_fragments) {
  const uint64_t wanted = capacity_for(previous_fragments);
  return previous_fragments > 0 && capacity > 2 * wanted ? wanted : 0;
}

// The most nodes a pool grown from `initial_per_pixel` x pixels by
// capacity_for() holds for a frame of `content` (its storage need, for
// TechniqueDescriptor::storage_need).
inline uint64_t nodes_for(const FrameContent& content, uint64_t initial_per_pixel) {
  return std::max(content.pixels() * initial_per_pixel, capacity_for(content.fragments));
}

// Slots per pixel a k-buffer allocates for a frame: k, or with k=auto the
// frame's longest list (at least 1, at most max_k).
inline uint64_t slots_per_pixel(const FrameContent& content, const ParamSet& params, int max_k) {
  if (!params.is_auto("k")) return uint64_t(params.integer("k"));
  return std::clamp<uint64_t>(content.longest_list, 1, uint64_t(max_k));
}

}  // namespace fragment_pool

class FragmentPool {
 public:
  // previous_frame: 1.25 x the last frame's fragments, grown on overflow;
  // exact: set_exact() before every fill (a counting pass), never overflows;
  // fixed: the capacity given to reset(), never changed.
  enum class Sizing { previous_frame, exact, fixed };

  // `largest_record_bytes`: the pool's largest per-node buffer, checked
  // against the device's largest storage block (and, read through a buffer
  // texture of `view_texel_bytes` texels, its largest buffer texture);
  // `smallest` nodes at least.
  FragmentPool(std::string owner, Sizing sizing, uint64_t largest_record_bytes,
               std::function<void(uint64_t capacity)> allocate, uint64_t smallest = 1, uint64_t view_texel_bytes = 16);

  // At the technique's resize(): `nodes` now, and no history.
  void reset(uint64_t nodes);
  // Before the fill of `frame` (previous_frame: shrinks a pool far above
  // every tile's last need).
  void before_fill(const Frame& frame);
  // A technique whose node layout depends on the scene (linearized_fragment_
  // buffer's flat-colour nodes) says the bytes of its largest record before
  // sizing; a change drops the buffers, which the next sizing allocates anew.
  void set_record_bytes(uint64_t largest_record_bytes);
  // exact: the frame's fragments, from a counting pass.
  void set_exact(uint64_t fragments);
  // After the fill: true when its `produced` fragments fit; otherwise the
  // pool has grown to hold them (a retry is counted) and the caller renders
  // the fill again.
  bool fits(const Frame& frame, uint64_t produced);
  // The fill loop of the list techniques, written once: stage "clear" runs
  // before_fill() and `clear`, stage "fill" runs `fill`, which draws the
  // scene and returns the fragments it produced; when they did not fit,
  // the pool has grown and both run again. Returns the fills run.
  uint64_t fill_until_fits(const Frame& frame, const std::function<void()>& clear,
                           const std::function<uint64_t()>& fill);

  uint64_t capacity() const { return capacity_; }
  uint64_t overflow_retries() const { return overflow_retries_; }

 private:
  void allocate(uint64_t capacity);

  std::string owner_;
  Sizing sizing_;
  uint64_t largest_record_bytes_, smallest_, view_texel_bytes_;
  std::function<void(uint64_t)> allocate_;
  uint64_t capacity_ = 0, overflow_retries_ = 0;
  std::vector<uint64_t> produced_by_tile_;  // the last fill of each tile (Frame::tile_index)
};

}  // namespace oit
