#pragma once
// How the fragment pools of the list-based techniques are sized: from the
// fragments a frame produced, plus slack, so that a similar next frame fits
// without an overflow re-render; a pool far above the need shrinks, but
// only past a factor 2, so that it does not reallocate every frame.
#include <algorithm>
#include <cstdint>

#include "core/technique.h"

namespace oit::fragment_pool {

// Nodes for `fragments` plus 25% slack (+1: never an empty pool).
constexpr uint64_t capacity_for(uint64_t fragments) { return fragments + fragments / 4 + 1; }

// The capacity to shrink to before a frame whose previous frame produced
// `previous_fragments` (none known: 0), or 0 to keep `capacity`.
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

}  // namespace oit::fragment_pool
