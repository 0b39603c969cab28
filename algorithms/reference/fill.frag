#version 450 core
#include "shaders/shading.glsl"
#include "algorithms/reference/reference_nodes.glsl"

void main() {
  uint pixel = uint(gl_FragCoord.y) * uint(u_width) + uint(gl_FragCoord.x);
  atomicMax(max_length, atomicAdd(lengths[pixel], 1u) + 1u);
  uint index = atomicAdd(node_count, 1u);
  if (index >= u_capacity) return;  // overflow: the host grows the pool and re-renders
  uint next = atomicExchange(heads[pixel], index);
  nodes[index] = ReferenceNode(oit_shade(), uvec4(floatBitsToUint(oit_view_depth()), oit_triangle_id(), next, 0u));
}
