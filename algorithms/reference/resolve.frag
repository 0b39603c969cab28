#version 450 core
// Exact resolve: each pixel's fragments are gathered into a local array
// (MAX_FRAGMENTS is compiled from the measured maximum list length, so no
// fragment is ever dropped), ordered by a 64-bit key (order-preserving bits
// of the view depth, then the stable triangle id: unique per pixel, so ties
// are broken deterministically) and blended front to back in double
// precision. `precise` forbids fused multiply-adds so the result is
// bit-identical to the closed form computed on the CPU.
#extension GL_ARB_gpu_shader_int64 : require
#include "shaders/compose.glsl"
#include "algorithms/reference/reference_nodes.glsl"

layout(location = 0) out vec4 out_color;

uint64_t sort_key(uvec4 link) {
  return (uint64_t(oit_depth_order(link.x)) << 32) | uint64_t(link.y);
}

uint64_t keys[MAX_FRAGMENTS];
uint indices[MAX_FRAGMENTS];

void main() {
  uint count = 0u;
  uint cursor = heads[oit_pixel_index(u_width)];
  while (cursor != REFERENCE_NIL && count < uint(MAX_FRAGMENTS)) {
    uvec4 link = nodes[cursor].link;
    keys[count] = sort_key(link);
    indices[count] = cursor;
    ++count;
    cursor = link.z;
  }
  // Insertion sort by key.
  for (uint i = 1u; i < count; ++i) {
    uint64_t key = keys[i];
    uint index = indices[i];
    int j = int(i) - 1;
    while (j >= 0 && keys[j] > key) {
      keys[j + 1] = keys[j];
      indices[j + 1] = indices[j];
      --j;
    }
    keys[j + 1] = key;
    indices[j + 1] = index;
  }
  precise dvec3 accumulated = dvec3(0.0);
  precise double transmittance = 1.0;
  for (uint i = 0u; i < count; ++i) {
    dvec4 c = dvec4(nodes[indices[i]].color);
    precise double weight = transmittance * c.a;
    accumulated += weight * c.rgb;
    transmittance *= 1.0 - c.a;
  }
  precise dvec3 result = accumulated + transmittance * dvec3(u_background);
  out_color = vec4(vec3(result), float(1.0 - transmittance));
}
