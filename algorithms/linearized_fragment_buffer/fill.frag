#version 450 core
// Fill pass of the linearized fragment buffer: every fragment takes the next
// free slot of its pixel's range, offset[pixel] + (an atomic increment of the
// pixel's own cursor), and writes its sort key and colour there. No global
// counter: the atomics of different pixels never touch the same word.
// Everything per-pixel-addressed is an image or buffer texture, not an SSBO:
// on llvmpipe those are vector gathers and scatters, an SSBO access with
// per-lane addresses a loop over the lanes (README: fill).
#include "shaders/shading.glsl"
#include "algorithms/linearized_fragment_buffer/storage.glsl"

// pixels + 1 exclusive prefix sums of the counts: pixel p owns [offset[p], offset[p+1]).
layout(binding = 1) uniform usamplerBuffer u_offsets;
// Fragments written so far per pixel (cleared before the fill): afterwards the list lengths.
layout(binding = 2, r32ui) coherent uniform uimageBuffer u_cursors;
layout(binding = 0, rg32ui) writeonly uniform uimageBuffer u_nodes;
layout(location = OIT_FIRST_TECHNIQUE_UNIFORM + 1) uniform int u_width;

void main() {
  const int pixel = int(gl_FragCoord.y) * u_width + int(gl_FragCoord.x);
  const uint slot = texelFetch(u_offsets, pixel).x + imageAtomicAdd(u_cursors, pixel, 1u);
  // No bounds check here (it cost ~10% of the fill): the resolve checks
  // every pixel's count against its range once (storage.glsl, lfb_check).
  const uvec4 color = floatBitsToUint(oit_shade());
  imageStore(u_nodes, lfb_key_texel(slot), uvec4(lfb_depth_order(floatBitsToUint(oit_view_depth())), oit_triangle_id(), 0u, 0u));
  imageStore(u_nodes, lfb_key_texel(slot) + 1, color.xyyy);
  imageStore(u_nodes, lfb_key_texel(slot) + 2, color.zwww);
}
