#version 450 core
#if defined(LFB_KEY64)
#extension GL_ARB_gpu_shader_int64 : require
#if !defined(LFB_FLAT_COLOR)
#error "LFB_KEY64 needs LFB_FLAT_COLOR: a 24-byte node keeps its key beside the colour"
#endif
#endif
#if defined(LFB_FETCH_CURSOR)
#extension GL_EXT_shader_framebuffer_fetch : require
#endif
// Fill pass of the linearized fragment buffer: every fragment takes the next
// free slot of its pixel's range (an atomic increment of the pixel's own
// cursor, which starts at the pixel's offset) and writes its node there. No global
// counter: the atomics of different pixels never touch the same word.
// Everything per-pixel-addressed is an image or buffer texture, not an SSBO:
// on llvmpipe those are vector gathers and scatters, an SSBO access with
// per-lane addresses a loop over the lanes (README: fill).
#include "shaders/shading.glsl"
#include "algorithms/linearized_fragment_buffer/storage.glsl"

// Pixel p owns slots [offset[p], offset[p+1]); its cursor starts at
// offset[p] (a copy of the prefix sum), so the atomic returns the slot.
// LFB_FETCH_CURSOR (fill=framebuffer_fetch): the cursor is the pixel's
// R32UI colour instead; framebuffer fetch is coherent, so the fragments of a
// pixel read and increment it one after the other in primitive order, as
// blending would, with no atomic (README: fill).
#if defined(LFB_FETCH_CURSOR)
layout(location = 0) inout uint cursor;
#else
layout(binding = LFB_CURSORS_IMAGE_UNIT, r32ui) uniform uimageBuffer u_cursors;
#endif
#if defined(LFB_KEY64)
// One 64-bit store per fragment: on llvmpipe one scalar store per lane,
// where the RG32UI imageStore costs two (README: key_format).
layout(std430, binding = LFB_KEYS_BINDING) writeonly buffer LfbKeys { uint64_t lfb_keys[]; };
#else
layout(binding = LFB_NODES_IMAGE_UNIT, rg32ui) writeonly uniform uimageBuffer u_nodes;
#endif

void main() {
  // No bounds check here: the resolve checks every pixel's range once.
#if defined(LFB_FETCH_CURSOR)
  const uint slot = cursor;
  cursor = slot + 1u;
#else
  const uint slot = imageAtomicAdd(u_cursors, int(oit_pixel_index(lfb.width)), 1u);
#endif
  const uvec2 key = uvec2(oit_depth_order(floatBitsToUint(oit_view_depth())), oit_triangle_id());
#if defined(LFB_KEY64)
  lfb_keys[slot] = packUint2x32(key.yx);
#else
  imageStore(u_nodes, lfb_key_texel(slot), lfb_texel_from_key(key));
#endif
#if !defined(LFB_FLAT_COLOR)
  const uvec4 color = floatBitsToUint(oit_shade());
  imageStore(u_nodes, lfb_key_texel(slot) + 1, color.xyyy);
  imageStore(u_nodes, lfb_key_texel(slot) + 2, color.zwww);
#endif
}
