#version 450 core
#include "shaders/subgroup_atomics.glsl"
#include "shaders/shading.glsl"
#include "algorithms/reference/reference_nodes.glsl"

void main() {
  uint pixel = oit_pixel_index(reference.width);
  OIT_ATOMIC_RAISE(max_length, atomicAdd(lengths[pixel], 1u) + 1u);
  uint index;
  OIT_ATOMIC_APPEND(node_count, index);
  if (index >= reference.capacity) return;  // overflow: the host grows the pool and re-renders
  uint next = atomicExchange(heads[pixel], index);
  nodes[index] = ReferenceNode(oit_shade(), uvec4(floatBitsToUint(oit_view_depth()), oit_triangle_id(), next, 0u));
}
