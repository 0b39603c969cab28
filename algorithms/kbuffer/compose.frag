#version 450 core
// Compose: blend the pixel's owned slots (already sorted by depth key)
// front to back, ordering runs of tied keys by triangle id (PAPER_SLOTS: by
// packed colour), then put the tail (if any) behind them.
#include "shaders/compose.glsl"
#include "algorithms/kbuffer/kbuffer_storage.glsl"
#include "algorithms/kbuffer/bindings.h"

#ifdef TAIL_BLEND
layout(binding = KBUFFER_TAIL_ACCUMULATION_UNIT) uniform sampler2D u_tail_accumulation;
layout(binding = KBUFFER_TAIL_REVEALAGE_UNIT) uniform sampler2D u_tail_revealage;
#endif

layout(location = 0) out vec4 out_color;

uint keys[K];
uint ties[K];
vec4 colors[K];

// Front-to-back blend of one slot into (accumulated, transmittance).
void blend(vec4 c, inout vec3 accumulated, inout float transmittance) {
  accumulated += (transmittance * c.a) * c.rgb;
  transmittance *= 1.0 - c.a;
}

void main() {
  const uint first = kbuffer_first_slot();
  vec3 accumulated = vec3(0.0);
  float transmittance = 1.0;
  // Common case: the keys are sorted and distinct, so the slots are blended
  // straight from the buffer as they come.
  uint count = 0u;
  bool tied = false;
  uint previous_key = KBUFFER_EMPTY;
  for (uint i = 0u; i < uint(slots.k); ++i) {
    const uint key = kbuffer_keys[first + i];
    if (key == KBUFFER_EMPTY) break;
    if (!kbuffer_filled(first + i)) continue;  // a key whose fragment went to the tail
    tied = tied || key == previous_key;
    previous_key = key;
    blend(kbuffer_color(first + i), accumulated, transmittance);
    ++count;
  }
  if (tied) {
    // Equal depth keys: which tied fragment claimed which slot depended on
    // timing, so gather the slots (one simple loop), order each run of tied
    // keys by triangle id (PAPER_SLOTS: by packed colour) with an insertion
    // sort (keys are sorted, so only ties move) and blend again in that
    // deterministic order.
    uint gathered = 0u;
    for (uint i = 0u; i < uint(slots.k); ++i) {
      const uint key = kbuffer_keys[first + i];
      if (key == KBUFFER_EMPTY) break;
      if (!kbuffer_filled(first + i)) continue;
      keys[gathered] = key;
      ties[gathered] = kbuffer_tie_word(first + i);
      colors[gathered] = kbuffer_color(first + i);
      ++gathered;
    }
    for (uint i = 1u; i < gathered; ++i) {
      const uint key = keys[i], tie = ties[i];
      const vec4 color = colors[i];
      int j = int(i) - 1;
      while (j >= 0 && (keys[j] > key || (keys[j] == key && ties[j] > tie))) {
        keys[j + 1] = keys[j];
        ties[j + 1] = ties[j];
        colors[j + 1] = colors[j];
        --j;
      }
      keys[j + 1] = key;
      ties[j + 1] = tie;
      colors[j + 1] = color;
    }
    accumulated = vec3(0.0);
    transmittance = 1.0;
    for (uint i = 0u; i < gathered; ++i) blend(colors[i], accumulated, transmittance);
  }
  if (count > 0u) atomicAdd(kbuffer_stored, count);
#ifdef TAIL_BLEND
  const ivec2 texel = ivec2(gl_FragCoord.xy);
  const vec4 tail = texelFetch(u_tail_accumulation, texel, 0);
  const float tail_revealage = texelFetch(u_tail_revealage, texel, 0).r;
  if (tail.a > 0.0) {
    // Average tail colour times the tail's exact total coverage.
    accumulated += transmittance * (tail.rgb / tail.a) * (1.0 - tail_revealage);
    transmittance *= tail_revealage;
  }
#endif
  out_color = oit_finish(accumulated, transmittance);
}
