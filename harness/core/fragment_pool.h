#pragma once
// How the fragment pools of the list-based techniques are sized: from the
// fragments a frame produced, plus slack, so that a similar next frame fits
// without an overflow re-render; a pool far above the need shrinks, but
// only past a factor 2, so that it does not reallocate every frame.
#include <cstdint>

namespace oit::fragment_pool {

// Nodes for `fragments` plus 25% slack (+1: never an empty pool).
constexpr uint64_t capacity_for(uint64_t fragments) { return fragments + fragments / 4 + 1; }

// The capacity to shrink to before a frame whose previous frame produced
// `previous_fragments` (none known: 0), or 0 to keep `capacity`.
constexpr uint64_t shrunk_capacity(uint64_t capacity, uint64_t previous_fragments) {
  const uint64_t wanted = capacity_for(previous_fragments);
  return previous_fragments > 0 && capacity > 2 * wanted ? wanted : 0;
}

}  // namespace oit::fragment_pool
