#version 450 core
// Exact resolve: each pixel's fragments are gathered into a local array
// (MAX_FRAGMENTS is compiled from the measured maximum list length, so no
// fragment is ever dropped), ordered by the key (order-preserving bits of
// the view depth, then the stable triangle id: unique per pixel, so ties are
// broken deterministically) and blended front to back in double precision.
// `precise` forbids fused multiply-adds so the result is bit-identical to the
// closed form computed on the CPU.
//
// The key is a uvec2 compared word by word, not one uint64: with the uint64
// key NVIDIA's driver 580 (H200) resolved 8 stacked quads to (0.504, 0.482,
// 0.266) where the closed form is (0.510, 0.478, 0.374); with the uvec2 key
// the image is exact there as on llvmpipe.
#include "shaders/compose.glsl"
#include "algorithms/reference/reference_nodes.glsl"

layout(location = 0) out vec4 out_color;

uvec2 sort_key(uvec4 link) { return uvec2(oit_depth_order(link.x), link.y); }

bool key_greater(uvec2 a, uvec2 b) { return a.x > b.x || (a.x == b.x && a.y > b.y); }

uvec2 keys[MAX_FRAGMENTS];
uint indices[MAX_FRAGMENTS];

void main() {
  uint count = 0u;
  uint cursor = heads[oit_pixel_index(reference.width)];
  while (cursor != REFERENCE_NIL && count < uint(MAX_FRAGMENTS)) {
    uvec4 link = nodes[cursor].link;
    keys[count] = sort_key(link);
    indices[count] = cursor;
    ++count;
    cursor = link.z;
  }
  // Insertion sort by key.
  for (uint i = 1u; i < count; ++i) {
    uvec2 key = keys[i];
    uint index = indices[i];
    int j = int(i) - 1;
    while (j >= 0 && key_greater(keys[j], key)) {
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
