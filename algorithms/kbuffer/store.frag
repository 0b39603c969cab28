#version 450 core
#include "shaders/subgroup_atomics.glsl"
// Pass 2 (store): the same fragments again. A fragment among the K nearest
// finds its depth key in the pixel's sorted keys (binary search for the
// first slot >= key) and writes its colour there. Tied keys (equal view
// depths) occupy consecutive slots; each tied fragment claims the first
// unowned one with atomicCompSwap on the owner word, writing its stable
// triangle id, and compose orders a tied run by that id: the same
// deterministic tie-break (depth, then triangle id) as the reference.
// PAPER_SLOTS: the packed colour word is itself the claim (cleared to 0),
// and compose orders ties by it.
// Fragments that find no free slot with their key are the tail.
#include "shaders/shading.glsl"
#include "algorithms/kbuffer/kbuffer_storage.glsl"

#ifdef TAIL_BLEND
// The tail's weighted average (Bavoil & Myers 2008, i.e. weighted blended
// OIT with weight 1): rgb += a * colour, a += a (additive blending) and
// revealage *= 1 - a (ZERO, ONE_MINUS_SRC_COLOR) into separate targets.
layout(location = 0) out vec4 out_tail_accumulation;
layout(location = 1) out vec4 out_tail_revealage;
#endif

void main() {
  const uint first = kbuffer_first_slot();
  const uint key = kbuffer_depth_key(oit_view_depth());
  const vec4 color = oit_shade();
  uint low = 0u, high = uint(slots.k);
  while (low < high) {
    const uint middle = (low + high) >> 1;
    if (kbuffer_keys[first + middle] < key) low = middle + 1u;
    else high = middle;
  }
#ifdef PAPER_SLOTS
  const uint rgba8 = packUnorm4x8(color);
#else
  const uint owner = oit_triangle_id();
#endif
  for (uint i = low; i < uint(slots.k) && kbuffer_keys[first + i] == key; ++i) {
#ifdef PAPER_SLOTS
    if (atomicCompSwap(kbuffer_packed[first + i], KBUFFER_NO_COLOR, rgba8) == KBUFFER_NO_COLOR) {
#else
    if (atomicCompSwap(kbuffer_owners[first + i], KBUFFER_EMPTY, owner) == KBUFFER_EMPTY) {
      kbuffer_colors[first + i] = color;
#endif
#ifdef TAIL_BLEND
      out_tail_accumulation = vec4(0.0);  // neutral for both blend equations
      out_tail_revealage = vec4(0.0);
#endif
      return;
    }
  }
  // Not among the K nearest.
#ifdef TAIL_BLEND
  out_tail_accumulation = vec4(color.rgb * color.a, color.a);
  out_tail_revealage = vec4(color.a);
#else
  OIT_ATOMIC_COUNT(kbuffer_dropped);
#endif
}
