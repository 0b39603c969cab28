#version 450 core
// Pass 1 (fill): keep the slots.k nearest depth keys of the pixel. The key is
// inserted from the first slot not below it onwards: each atomicMin leaves
// the smaller of (slot, key) in the slot and carries the larger on, so
// concurrent insertions never lose a key and the slots stay sorted. A key
// carried past the last slot belongs to the tail.
#include "shaders/shading.glsl"
#include "algorithms/hybrid_transparency/core_storage.glsl"

void main() {
  if (core_skips(oit_shade())) return;
  const uint first = core_first_slot();
  uint key = core_depth_key(oit_view_depth());
  // Slots only decrease and stay sorted, so a slot read below the key stays
  // below it: starting at the lower bound skips atomics that change nothing.
  for (uint i = core_lower_bound(first, key); i < uint(slots.k); ++i) {
    const uint displaced = atomicMin(core_keys[first + i], key);
    if (displaced == CORE_EMPTY) return;
    key = max(key, displaced);
  }
}
