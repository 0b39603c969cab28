// Storage and packing shared by every pass of the bucketed k-buffer
// (murray2016 section 4). Compile-time defines: K (slots per pixel, 1..64),
// DEPTH_BITS (16 or 24); the sort, store and neighbour passes also take BUCKETS:
// BKB_BUCKETS_HASHED finds a shape's bucket in the hash table of the bucket
// pass, BKB_BUCKETS_SINGLE treats the whole list as one bucket (one-object
// scenes: no hash table is built), BKB_BUCKETS_NONE (neighbour pass only,
// buckets=off) is the brute force of murray2016 Figure 10. Every per-pixel array is pixel-major: slot i of
// pixel p is element p * K + i, so one pixel's list is contiguous.
#include "algorithms/bucketed_kbuffer/bindings.h"

#define BKB_EMPTY 0xffffffffu
#define BKB_BUCKETS_NONE 0
#define BKB_BUCKETS_HASHED 1
#define BKB_BUCKETS_SINGLE 2
#if DEPTH_BITS == 24
// 24-bit depth + 8-bit shape id (at most 256 objects).
#define BKB_SHAPE_BITS 8u
#define BKB_DEPTH_MAX 16777214u
#else
// The paper's packing: 16-bit depth + 16-bit shape id.
#define BKB_SHAPE_BITS 16u
#define BKB_DEPTH_MAX 65534u
#endif
#define BKB_SHAPE_MASK ((1u << BKB_SHAPE_BITS) - 1u)
#define BKB_DEPTH_MASK ((1u << (32u - BKB_SHAPE_BITS)) - 1u)
// Bit 31 of a stored normal marks a slot claimed by the data pass, so a
// cleared (zero) normal word means "no data stored here".
#define BKB_NORMAL_WRITTEN 0x80000000u

// Z: per slot a 32-bit key. After the fill pass: depth in the high bits
// (atomicMin keeps the nearest); after the sort pass: shape id in the high bits.
layout(std430, binding = BKB_Z_BINDING) coherent buffer BkbZ { uint bkb_z[]; };
// B: per pixel a hash table of K buckets: shape id << 16 | first << 8 | last
// (BKB_BUCKETS_SINGLE: only the first word, the list's length).
layout(std430, binding = BKB_BUCKETS_BINDING) coherent buffer BkbBuckets { uint bkb_buckets[]; };
// D, split in two arrays: packed RGBA8 colour and packed normal.
layout(std430, binding = BKB_COLORS_BINDING) coherent buffer BkbColors { uint bkb_colors[]; };
layout(std430, binding = BKB_NORMALS_BINDING) coherent buffer BkbNormals { uint bkb_normals[]; };
// Per slot: kappa as float16 (low 16 bits) | found-neighbour mask << 16.
layout(std430, binding = BKB_FEATURES_BINDING) coherent buffer BkbFeatures { uint bkb_features[]; };
layout(std430, binding = BKB_COUNTERS_BINDING) coherent buffer BkbCounters { uint bkb_dropped; };
// Diagnostics, bound only with measure_accuracy: neighbour slot per direction
// (8 bits each, 0xff = missing), the analytic and the estimated k1 + k2.
layout(std430, binding = BKB_LINKS_BINDING) coherent buffer BkbLinks { uint bkb_links[]; };
layout(std430, binding = BKB_EXPECTED_BINDING) coherent buffer BkbExpected { float bkb_expected[]; };
layout(std430, binding = BKB_ESTIMATED_BINDING) coherent buffer BkbEstimated { float bkb_estimated[]; };
// Ground truth of the link precision/recall, measure_accuracy only: per slot
// surface id, (u, v) bits and the uv footprint of one pixel (fwidth, half2).
layout(std430, binding = BKB_TRUTH_BINDING) coherent buffer BkbTruth { uvec4 bkb_truth[]; };

layout(std140, binding = BKB_FRAME_PARAMS_BLOCK) uniform BkbFrameBlock { BkbFrameParams bkb; };

uint bkb_pixel_base(ivec2 pixel) { return (uint(pixel.y) * uint(bkb.width) + uint(pixel.x)) * uint(K); }
uint bkb_pixel_base() { return bkb_pixel_base(ivec2(gl_FragCoord.xy)); }

uint bkb_quantise_depth(float view_depth) {
  float t = clamp((view_depth - bkb.depth_near) / (bkb.depth_far - bkb.depth_near), 0.0, 1.0);
  return min(uint(t * float(BKB_DEPTH_MAX) + 0.5), BKB_DEPTH_MAX);
}

// Depth-major key of the fill pass; never equals BKB_EMPTY because the
// quantised depth stops one below the all-ones value.
uint bkb_depth_key(uint depth, uint shape) { return (depth << BKB_SHAPE_BITS) | (shape & BKB_SHAPE_MASK); }
// Depth-major -> shape-major (the reorder pass's swap).
uint bkb_swap_to_shape_major(uint key) {
  return ((key & BKB_SHAPE_MASK) << (32u - BKB_SHAPE_BITS)) | (key >> BKB_SHAPE_BITS);
}
uint bkb_shape_key(uint shape, uint depth) { return ((shape & BKB_SHAPE_MASK) << (32u - BKB_SHAPE_BITS)) | depth; }
uint bkb_shape(uint shape_key) { return shape_key >> (32u - BKB_SHAPE_BITS); }
uint bkb_depth(uint shape_key) { return shape_key & BKB_DEPTH_MASK; }
float bkb_depth_unit(uint shape_key) { return float(bkb_depth(shape_key)) / float(BKB_DEPTH_MAX); }
float bkb_view_depth(uint shape_key) {
  return mix(bkb.depth_near, bkb.depth_far, bkb_depth_unit(shape_key));
}

// 15 bits x, 15 bits y, 1 bit sign of z, 1 bit "written" (murray2016 4.2:
// 15 + 15 bits and the sign of z; the spare bit marks a claimed slot).
uint bkb_pack_normal(vec3 n) {
  uvec2 q = uvec2(round(clamp(n.xy * 0.5 + 0.5, 0.0, 1.0) * 32767.0));
  return BKB_NORMAL_WRITTEN | (n.z < 0.0 ? 0x40000000u : 0u) | (q.y << 15) | q.x;
}
// `precise`: one word unpacks to the same bits wherever it is unpacked
// (no multiply-add fused at one call site and not at another).
vec3 bkb_unpack_normal(uint word) {
  precise vec2 xy = vec2(uvec2(word & 0x7fffu, (word >> 15) & 0x7fffu)) * (2.0 / 32767.0) - 1.0;
  precise float z = sqrt(max(0.0, 1.0 - dot(xy, xy)));
  return vec3(xy, (word & 0x40000000u) != 0u ? -z : z);
}

// A pixel's whole list as one bucket (BKB_BUCKETS_SINGLE: buckets=single, auto on
// a one-object scene, where the bucket pass does not run): the sort pass
// writes the list's length to the first word of the pixel's bucket table.
// The scene rectangle's scissor can leave that word stale outside the
// rectangle, but there slot 0 of Z is always cleared (BKB_EMPTY), which is
// checked first. Returns the slot range [first, last]; empty (x > y) when
// the pixel kept nothing.
uvec2 bkb_whole_list(uint base) {
  uint count = bkb_z[base] == BKB_EMPTY ? 0u : bkb_buckets[base];
  return count == 0u ? uvec2(1u, 0u) : uvec2(0u, count - 1u);
}

// Figure 4 (1)-(2): the bucket of `shape` in a pixel's hash table,
// H(b) = b mod K with linear probing. Returns false when the pixel kept no
// fragment of that shape.
bool bkb_find_bucket(uint base, uint shape, out uvec2 range) {
  uint slot = shape % uint(K);
  range = uvec2(0u);
  for (int probe = 0; probe < K; ++probe) {
    uint entry = bkb_buckets[base + slot];
    if (entry == BKB_EMPTY) return false;
    if ((entry >> 16) == shape) {
      range = uvec2((entry >> 8) & 0xffu, entry & 0xffu);
      return true;
    }
    slot = slot + 1u == uint(K) ? 0u : slot + 1u;
  }
  return false;
}
