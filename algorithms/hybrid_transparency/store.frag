#version 450 core
// Pass 2 (store): a fragment among the slots.k nearest finds its key's slot
// and claims it by writing its packed colour there (atomicCompSwap from 0,
// so equal keys take consecutive slots one each); every other fragment is
// the tail, accumulated order-independently as the weighted average of
// Bavoil & Myers 2008: (sum a rgb, sum a) and the fragment count n.
#include "shaders/subgroup_atomics.glsl"
#include "shaders/shading.glsl"
#include "algorithms/hybrid_transparency/core_storage.glsl"

layout(location = 0) out vec4 out_tail_sum;
layout(location = 1) out vec4 out_tail_count;

void main() {
  const vec4 color = oit_shade();
  out_tail_sum = vec4(0.0);
  out_tail_count = vec4(0.0);
  if (core_skips(color)) return;
  const uint first = core_first_slot();
  const uint key = core_depth_key(oit_view_depth());
  const uint packed_color = packUnorm4x8(color);
  for (uint i = core_lower_bound(first, key); i < uint(slots.k) && core_keys[first + i] == key; ++i) {
    if (atomicCompSwap(core_colors[first + i], 0u, packed_color) == 0u) return;
  }
  // A key equal to the last core key can find its run of slots full when
  // more fragments share it than fit: it joins the tail and is counted.
  if (core_lower_bound(first, key) < uint(slots.k)) OIT_ATOMIC_COUNT(core_tied_to_tail);
  out_tail_sum = vec4(color.rgb * color.a, color.a);
  out_tail_count = vec4(1.0);
}
