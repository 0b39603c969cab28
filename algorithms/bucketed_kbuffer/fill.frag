#version 450 core
#include "shaders/subgroup_atomics.glsl"
// Z pass (murray2016 4.1 "Z insertion", 4.2): the K nearest fragments of
// each pixel as depth-major 32-bit keys (depth | shape id), kept sorted by a
// chain of 32-bit atomicMin: each slot keeps the smaller key and the larger
// one moves on to the next slot. What falls off the last slot is counted.
#include "shaders/shading.glsl"
#include "algorithms/bucketed_kbuffer/bkb_common.glsl"

void main() {
  uint carried = bkb_depth_key(bkb_quantise_depth(oit_view_depth()), v_object_id);
  uint base = bkb_pixel_base();
  // Slots only ever decrease during this pass, so a plain read may skip
  // atomics: a slot already <= the carried key keeps its value, and a key
  // above the last slot can never be among the K nearest.
  if (carried > bkb_z[base + uint(K - 1)]) {
    OIT_ATOMIC_COUNT(bkb_dropped);
    return;
  }
  for (int i = 0; i < K; ++i) {
    if (bkb_z[base + uint(i)] <= carried) continue;
    uint previous = atomicMin(bkb_z[base + uint(i)], carried);
    if (previous == BKB_EMPTY) return;  // took a free slot
    carried = max(previous, carried);
  }
  OIT_ATOMIC_COUNT(bkb_dropped);  // beyond the K nearest
}
