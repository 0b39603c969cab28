#version 450 core
#include "shaders/subgroup_atomics.glsl"
// Fill (carnecky2013 Algorithm 1, pastyrik2016 Algorithm 1): every fragment
// is appended to its pixel's list with its colour, depth, slopes, normal,
// object and triangle id. The list length is counted even when the pool is
// full, so the host learns how many records it needs (overflow -> grow and
// render again) and how long the longest list is.
#include "shaders/shading.glsl"
#include "algorithms/illustration_buffer/ib_storage.glsl"

layout(location = IB_CAPACITY_LOCATION) uniform uint u_capacity;
layout(location = IB_MAX_PER_PIXEL_LOCATION) uniform uint u_max_per_pixel;

#ifdef IB_MEASURE
// Ground truth for the neighbour accuracy only (parameter measure_accuracy):
// x: surface id, yz: (u, v) bits, w: uv footprint of one pixel (fwidth, half2).
layout(std430, binding = IB_TRUTH_BINDING) buffer IbTruth { uvec4 ib_truth[]; };
#endif

void main() {
  // Derivatives first, in uniform control flow (before any early return).
  const float depth = oit_view_depth();
  const vec2 slopes = vec2(dFdx(depth), dFdy(depth));
#ifdef IB_MEASURE
  const vec2 footprint = fwidth(v_uv);
#endif
  const uint pixel = uint(gl_FragCoord.y) * uint(u_width) + uint(gl_FragCoord.x);
  const uint position = atomicAdd(ib_count[pixel], 1u);
  OIT_ATOMIC_RAISE(ib_longest, position + 1u);
  // Beyond the sort's array: counted here; the sort keeps the nearest max_per_pixel.
  if (position >= u_max_per_pixel) {
    OIT_ATOMIC_COUNT(ib_dropped);
    if (position == u_max_per_pixel) atomicAdd(ib_truncated, 1u);
  }
  uint index;
  OIT_ATOMIC_APPEND(ib_produced, index);
  if (index >= u_capacity) return;  // pool overflow: the host grows the pool and re-renders
  ib_next[index] = atomicExchange(ib_head[pixel], index);
  const uvec4 key = uvec4(floatBitsToUint(depth), oit_triangle_id(), v_object_id, ib_pack_normal(oit_view_normal()));
  ib_fragments[index] = IbFragment(oit_shade(), key, vec4(slopes, 0.0, 0.0));
#ifdef IB_MEASURE
  ib_truth[index] = uvec4(v_surface_id, floatBitsToUint(v_uv.x), floatBitsToUint(v_uv.y), packHalf2x16(footprint));
#endif
}
