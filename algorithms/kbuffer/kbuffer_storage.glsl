// Storage of the dual-pass k-buffer: per pixel, k slots of (depth key, owner,
// RGBA32F colour), or with PAPER_SLOTS (slot_layout=paper) of (depth key,
// RGBA8 colour); pixel-major (slot i of pixel p at p * k + i) so that one
// pixel's keys are contiguous: llvmpipe shades a pixel on one CPU thread, and its
// cache lines then hold a whole pixel's list.
#include "shaders/bindings.h"
#include "shaders/pixel_slots.glsl"
#include "algorithms/kbuffer/bindings.h"

#define KBUFFER_EMPTY 0xffffffffu

// Sorted ascending per pixel by the fill pass; EMPTY slots come last.
layout(std430, binding = KBUFFER_KEYS_BINDING) coherent buffer KBufferKeys { uint kbuffer_keys[]; };
#ifdef PAPER_SLOTS
// slot_layout=paper (murray2016 section 6: "64 bits per fragment"): per slot
// only the key and the RGBA8 colour, packed. The colour word doubles as the
// claim: cleared to 0 and claimed with atomicCompSwap by the store pass, so
// 0 = no colour stored (a fragment whose RGBA8 colour is all zero adds
// nothing to the blend and stays uncounted). Ties are ordered by the packed
// colour: no owner word is kept.
layout(std430, binding = KBUFFER_COLORS_BINDING) coherent buffer KBufferPackedColors { uint kbuffer_packed[]; };
#define KBUFFER_NO_COLOR 0u
bool kbuffer_filled(uint slot) { return kbuffer_packed[slot] != KBUFFER_NO_COLOR; }
// The word that orders a run of tied keys in compose.
uint kbuffer_tie_word(uint slot) { return kbuffer_packed[slot]; }
vec4 kbuffer_color(uint slot) { return unpackUnorm4x8(kbuffer_packed[slot]); }
#else
// Stable triangle id of the fragment whose colour the slot holds, claimed by
// the store pass with atomicCompSwap; EMPTY = no colour stored. It makes
// tied depth keys resolvable (see store.frag) and marks valid slots.
layout(std430, binding = KBUFFER_OWNERS_BINDING) coherent buffer KBufferOwners { uint kbuffer_owners[]; };
// Straight RGBA of the slot, read and written as whole vec4s (Mesa 22.3
// llvmpipe misreads scalar members of struct arrays inside loops).
layout(std430, binding = KBUFFER_COLORS_BINDING) buffer KBufferColors { vec4 kbuffer_colors[]; };
bool kbuffer_filled(uint slot) { return kbuffer_owners[slot] != KBUFFER_EMPTY; }
uint kbuffer_tie_word(uint slot) { return kbuffer_owners[slot]; }
vec4 kbuffer_color(uint slot) { return kbuffer_colors[slot]; }
#endif
// stored: fragments composed from the slots (added by compose, per pixel);
// dropped: fragments beyond the K nearest whose colour was discarded.
layout(std430, binding = KBUFFER_COUNTERS_BINDING) coherent buffer KBufferCounters {
  uint kbuffer_stored;
  uint kbuffer_dropped;
};

// The frame's width and k: the shared parameter block of k slots per pixel
// (shaders/pixel_slots.h), `slots`.
uint kbuffer_first_slot() { return slots_pixel() * uint(slots.k); }

// 32-bit sort key of a view depth. Only the all-ones pattern (a NaN) would
// collide with EMPTY, so it is clamped below it. Equal depths give equal
// keys: ties are resolved by the store pass, not here.
uint kbuffer_depth_key(float depth) { return min(oit_depth_order(floatBitsToUint(depth)), KBUFFER_EMPTY - 1u); }
