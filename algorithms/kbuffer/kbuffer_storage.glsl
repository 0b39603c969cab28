// Storage of the dual-pass k-buffer: per pixel, u_k slots of (depth key, owner,
// colour), pixel-major (slot i of pixel p at p * u_k + i) so that one pixel's
// keys are contiguous: llvmpipe shades a pixel on one CPU thread, and its
// cache lines then hold a whole pixel's list.
#include "shaders/bindings.h"
#include "shaders/pixel_storage.glsl"
#include "algorithms/kbuffer/bindings.h"

#define KBUFFER_EMPTY 0xffffffffu

// Sorted ascending per pixel by the fill pass; EMPTY slots come last.
layout(std430, binding = KBUFFER_KEYS_BINDING) coherent buffer KBufferKeys { uint kbuffer_keys[]; };
// Stable triangle id of the fragment whose colour the slot holds, claimed by
// the store pass with atomicCompSwap; EMPTY = no colour stored. It makes
// tied depth keys resolvable (see store.frag) and marks valid slots.
layout(std430, binding = KBUFFER_OWNERS_BINDING) coherent buffer KBufferOwners { uint kbuffer_owners[]; };
// Straight RGBA of the slot, read and written as whole vec4s (Mesa 22.3
// llvmpipe misreads scalar members of struct arrays inside loops).
layout(std430, binding = KBUFFER_COLORS_BINDING) buffer KBufferColors { vec4 kbuffer_colors[]; };
// stored: fragments composed from the slots (added by compose, per pixel);
// dropped: fragments beyond the K nearest whose colour was discarded.
layout(std430, binding = KBUFFER_COUNTERS_BINDING) coherent buffer KBufferCounters {
  uint kbuffer_stored;
  uint kbuffer_dropped;
};

layout(location = KBUFFER_WIDTH_LOCATION) uniform int u_width;
// Slots per pixel, 1 <= u_k <= K. A uniform, not the define K: with k=auto
// one program (K = the next power of two) serves every k up to K, and loops
// bounded by a uniform are not unrolled, which made compose faster on
// llvmpipe (README, "k=auto"). K only sizes compose's local arrays.
layout(location = KBUFFER_SLOTS_LOCATION) uniform int u_k;

uint kbuffer_first_slot() { return oit_pixel_index(u_width) * uint(u_k); }

// 32-bit sort key of a view depth. Only the all-ones pattern (a NaN) would
// collide with EMPTY, so it is clamped below it. Equal depths give equal
// keys: ties are resolved by the store pass, not here.
uint kbuffer_depth_key(float depth) { return min(oit_depth_order(floatBitsToUint(depth)), KBUFFER_EMPTY - 1u); }
