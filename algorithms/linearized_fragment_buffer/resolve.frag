#version 450 core
#if defined(LFB_KEY64)
#extension GL_ARB_gpu_shader_int64 : require
#endif
// Resolve of the linearized fragment buffer: each pixel's keys lie in one
// contiguous range [offset, offset + length), read in order. Drawn per length
// class (backwards memory allocation, linked_list/length_classes.h: tiles by
// their longest list) or full screen; LL_CAPACITY is the class's array.
//
// LFB_NETWORK: the whole range goes into registers (constant indices only)
// and is sorted by linked_list's generated odd-even merge network
// (sorting_network.h: LL_LOAD_ALL, LL_NETWORK, LL_BLEND_ALL, LL_CE). With
// LFB_KEY64 (flat nodes, 64-bit keys) an element is the key as one uint64
// and a compare-exchange is one 64-bit min and max.
// LFB_BLOCKS (register-based block sort, Knowles et al. 2014): blocks of
// LL_CAPACITY fragments are loaded into registers one after the other,
// sorted there by the network of the block size and written back sorted into
// the pixel's own range (keys and colours); then a LFB_BLOCKS-way merge of
// the sorted blocks, their heads in registers, blends front to back.
#include "shaders/compose.glsl"
#include "algorithms/linearized_fragment_buffer/storage.glsl"

layout(location = 0) out vec4 out_color;
#if defined(LFB_BLOCKS)
layout(binding = LFB_NODES_IMAGE_UNIT, rg32ui) uniform uimageBuffer u_nodes;
#else
layout(binding = LFB_NODES_IMAGE_UNIT, rg32ui) readonly uniform uimageBuffer u_nodes;
#endif
uvec2 key_of(uint slot) { return lfb_key_from_texel(imageLoad(u_nodes, lfb_key_texel(slot)).xy); }
#if defined(LFB_FLAT_COLOR)
// The scene's flat colour of each stable triangle id (storage.glsl).
layout(binding = LFB_FLAT_COLORS_UNIT) uniform samplerBuffer u_flat_colors;
#endif
// The colour of element e (x: key, y: triangle id, z: slot; below).
vec4 color_of(uvec3 e) {
#if defined(LFB_FLAT_COLOR)
  return texelFetch(u_flat_colors, int(e.y));
#else
  const int at = lfb_key_texel(e.z);
  return uintBitsToFloat(uvec4(imageLoad(u_nodes, at + 1).xy, imageLoad(u_nodes, at + 2).xy));
#endif
}
layout(binding = LFB_OFFSETS_UNIT) uniform usamplerBuffer u_offsets;
// The list lengths (the counting pass's counts); classify.comp reads them too.
layout(binding = LFB_LENGTHS_UNIT) uniform usamplerBuffer u_lengths;

// Every pixel's cursor started at its offset and went up once per fragment
// the fill wrote, so it must end at offset + length. A pixel where it does
// not is counted, and the host fails the frame: the counting pass and the
// fill rasterized different fragments (never expected: the same geometry
// under the same state), so the fill wrote into another pixel's range. One
// check per pixel here instead of a bounds check per fragment in the fill,
// where it was a measurable part of the fill's time.
#if defined(LFB_FETCH_CURSOR)
layout(binding = LFB_FINAL_CURSORS_UNIT) uniform usampler2D u_final_cursors;  // the fill's R32UI target
uint final_cursor(int pixel) { return texelFetch(u_final_cursors, ivec2(pixel % lfb.width, pixel / lfb.width), 0).x; }
#else
layout(binding = LFB_FINAL_CURSORS_UNIT) uniform usamplerBuffer u_final_cursors;  // the fill's cursor buffer
uint final_cursor(int pixel) { return texelFetch(u_final_cursors, pixel).x; }
#endif
layout(std430, binding = LFB_MISMATCHED_BINDING) coherent buffer LfbMismatched { uint lfb_mismatched_pixels; };
void check_range(int pixel, uint base, uint length) {
  if (final_cursor(pixel) != base + length) atomicAdd(lfb_mismatched_pixels, 1u);
}

vec3 accumulated = vec3(0.0);
float transmittance = 1.0;

// Front-to-back "under" in the reference's operation order, in float.
void blend(vec4 c) {
  const float weight = transmittance * c.a;
  accumulated += weight * c.rgb;
  transmittance *= 1.0 - c.a;
}

// Element: x = view depth in unsigned order, y = stable triangle id (the
// tie-break: unique per pixel, so the order is submission independent),
// z = slot. Padding sorts after every real fragment.
#define LFB_PAD uvec3(0xffffffffu, 0xffffffffu, 0u)
bool precedes(uvec3 a, uvec3 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

// Constant indices only (every macro expands to literals): the elements stay
// in registers; a runtime-indexed array is memory, accessed lane by lane on llvmpipe.
uvec3 e[LL_CAPACITY];
#define LL_CE(i, j) { \
    const bool swap_ij = precedes(e[j], e[i]); \
    const uvec3 first_ij = swap_ij ? e[j] : e[i]; \
    e[j] = swap_ij ? e[i] : e[j]; \
    e[i] = first_ij; }
// Element i of the range from `base` holding `available` fragments; past
// them, padding (the load re-reads the last slot instead of the next pixel's).
#define LL_LOAD(i) { \
    const uint at_i = base + min(uint(i), max(available, 1u) - 1u); \
    e[i] = uint(i) < available ? uvec3(key_of(at_i), at_i) : LFB_PAD; }

#if defined(LFB_NETWORK) && defined(LFB_KEY64)
// The key as (depth << 32 | triangle id): the same order as precedes().
#undef LL_CE
#undef LL_LOAD
uint64_t e64[LL_CAPACITY];
#define LL_CE(i, j) { \
    const uint64_t first_ij = min(e64[i], e64[j]); \
    e64[j] = max(e64[i], e64[j]); \
    e64[i] = first_ij; }
#define LL_LOAD(i) { \
    const uint at_i = base + min(uint(i), max(available, 1u) - 1u); \
    e64[i] = uint(i) < available ? packUint2x32(key_of(at_i).yx) : 0xffffffffffffffffUL; }
#define LL_BLEND(i) if (uint(i) < available) blend(texelFetch(u_flat_colors, int(unpackUint2x32(e64[i]).x)));
#elif defined(LFB_NETWORK)
#define LL_BLEND(i) if (uint(i) < available) blend(color_of(e[i]));
#endif

#if defined(LFB_NETWORK)

void main() {
  const int pixel = int(oit_pixel_index(lfb.width));
  const uint base = texelFetch(u_offsets, pixel).x;
  const uint available = texelFetch(u_lengths, pixel).x;
  check_range(pixel, base, available);
  LL_LOAD_ALL
  LL_NETWORK
  LL_BLEND_ALL
  out_color = oit_finish(accumulated, transmittance);
}

#elif defined(LFB_BLOCKS)
// After the block's network: its colours are read first, then keys and
// colours are written back in sorted order (reads before writes: a slot may
// be both read and overwritten). Each pixel owns its range: no races. Flat
// colours live in the scene's table: only the keys move.
#if defined(LFB_FLAT_COLOR)
#define LFB_FETCH(i)
#define LFB_STORE(i) if (uint(i) < available) imageStore(u_nodes, lfb_key_texel(base + uint(i)), lfb_texel_from_key(e[i].xy));
#else
vec4 colors[LL_CAPACITY];
#define LFB_FETCH(i) if (uint(i) < available) colors[i] = color_of(e[i]);
#define LFB_STORE(i) if (uint(i) < available) { \
    const int at_i = lfb_key_texel(base + uint(i)); \
    const uvec4 bits_i = floatBitsToUint(colors[i]); \
    imageStore(u_nodes, at_i, e[i].xyyy); \
    imageStore(u_nodes, at_i + 1, bits_i.xyyy); \
    imageStore(u_nodes, at_i + 2, bits_i.zwww); }
#endif
#define LFB_SORT_BLOCK(b) { \
    const uint base = start + uint(b) * uint(LL_CAPACITY); \
    const uint available = count - min(count, uint(b) * uint(LL_CAPACITY)); \
    LL_LOAD_ALL LL_NETWORK LFB_FETCH_ALL LFB_STORE_ALL }
// Block k's end, and its head: the next unmerged key of the block.
#define LFB_END(k) (start + min(count, uint((k) + 1) * uint(LL_CAPACITY)))
#define LFB_HEAD(k) { \
    const uint at_k = start + uint(k) * uint(LL_CAPACITY); \
    heads[k] = at_k < LFB_END(k) ? uvec3(key_of(at_k), at_k) : LFB_PAD; }
#define LFB_PICK(k) if (precedes(heads[k], nearest)) { nearest = heads[k]; winner = uint(k); }
#define LFB_ADVANCE(k) if (winner == uint(k)) heads[k] = next < LFB_END(k) ? uvec3(next_key, next) : LFB_PAD;

uvec3 heads[LFB_BLOCKS];

void main() {
  const int pixel = int(oit_pixel_index(lfb.width));
  const uint start = texelFetch(u_offsets, pixel).x;
  const uint count = texelFetch(u_lengths, pixel).x;
  check_range(pixel, start, count);
  // A loop over the blocks, the network unrolled inside: code size grows with
  // the block, not with the list (unrolled over 16 blocks of 16, a 256-array
  // took llvmpipe most of a minute to compile).
  for (uint b = 0u; b < uint(LFB_BLOCKS); ++b) LFB_SORT_BLOCK(b)
  LFB_HEAD_ALL
  const uint last = start + max(count, 1u) - 1u;
  for (uint n = 0u; n < count; ++n) {
    uvec3 nearest = heads[0];
    uint winner = 0u;
    LFB_PICK_ALL
    blend(color_of(nearest));
    // One load for whichever block advances (the slot after the winner's).
    const uint next = nearest.z + 1u;
    const uvec2 next_key = key_of(min(next, last));
    LFB_ADVANCE_ALL
  }
  out_color = oit_finish(accumulated, transmittance);
}
#else
#error "resolve.frag: define LFB_NETWORK or LFB_BLOCKS"
#endif
