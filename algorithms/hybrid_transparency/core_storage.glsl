// Hybrid transparency's core: per pixel, slots.k slots of (depth key, packed
// colour), pixel-major (slot i of pixel p at p * slots.k + i) so one pixel's
// slots share cache lines on the CPU thread that shades it. 8 bytes a slot:
// the paper's budget of one 32-bit depth and one RGBA8 colour per core
// fragment.
#include "shaders/bindings.h"
#include "shaders/pixel_slots.glsl"
#include "algorithms/hybrid_transparency/bindings.h"

#define CORE_EMPTY 0xffffffffu

// The slots.k smallest depth keys of the pixel, ascending; EMPTY slots last.
layout(std430, binding = HYBRID_TRANSPARENCY_KEYS_BINDING) coherent buffer CoreKeys { uint core_keys[]; };
// packUnorm4x8 of the straight RGBA of the fragment in that slot; 0 = not
// claimed (a fragment whose packed colour would be 0 has alpha < 1/510 and
// is treated as fully transparent, see hybrid_transparency.cpp).
layout(std430, binding = HYBRID_TRANSPARENCY_COLORS_BINDING) coherent buffer CoreColors { uint core_colors[]; };
// stored: core fragments composed (added by compose, per pixel);
// tied_to_tail: fragments whose key is in the core but whose run of equal
// keys was full (more ties than slots left), composed in the tail.
layout(std430, binding = HYBRID_TRANSPARENCY_COUNTERS_BINDING) coherent buffer CoreCounters {
  uint core_stored;
  uint core_tied_to_tail;
};

uint core_first_slot() { return slots_pixel() * uint(slots.k); }

// Unsigned key that orders like the float view depth, kept below EMPTY.
uint core_depth_key(float depth) { return min(oit_depth_order(floatBitsToUint(depth)), CORE_EMPTY - 1u); }

// The first slot whose key is >= key (slots.k when none): the keys are sorted.
uint core_lower_bound(uint first, uint key) {
  uint low = 0u, high = uint(slots.k);
  while (low < high) {
    const uint middle = (low + high) / 2u;
    if (core_keys[first + middle] < key) low = middle + 1u;
    else high = middle;
  }
  return low;
}

// Fully transparent fragments add nothing anywhere: both passes skip them.
bool core_skips(vec4 color) { return packUnorm4x8(color) == 0u || color.a <= 0.0; }
