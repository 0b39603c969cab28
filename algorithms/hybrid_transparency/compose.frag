#version 450 core
// Compose: the core's slots front to back, exactly (the keys are sorted),
// then the tail behind them as one layer of the average colour
// sum(a rgb) / sum(a) and the opacity 1 - (1 - mean a)^n that n layers of
// the mean opacity would have (Maule et al. 2013, after Bavoil & Myers).
#include "shaders/compose.glsl"
#include "algorithms/hybrid_transparency/core_storage.glsl"
#include "algorithms/hybrid_transparency/bindings.h"

layout(binding = HYBRID_TRANSPARENCY_TAIL_SUM_UNIT) uniform sampler2D u_tail_sum;
layout(binding = HYBRID_TRANSPARENCY_TAIL_COUNT_UNIT) uniform sampler2D u_tail_count;

layout(location = 0) out vec4 out_color;

void main() {
  const uint first = core_first_slot();
  vec3 accumulated = vec3(0.0);
  float transmittance = 1.0;
  uint stored = 0u;
  for (uint i = 0u; i < uint(slots.k); ++i) {
    const uint packed_color = core_colors[first + i];
    if (core_keys[first + i] == CORE_EMPTY) break;
    if (packed_color == 0u) continue;  // defensive: store gives every core key its fragment
    const vec4 c = unpackUnorm4x8(packed_color);
    accumulated += transmittance * c.a * c.rgb;
    transmittance *= 1.0 - c.a;
    ++stored;
  }
  if (stored > 0u) atomicAdd(core_stored, stored);
  const ivec2 texel = ivec2(gl_FragCoord.xy);
  const vec4 tail = texelFetch(u_tail_sum, texel, 0);
  const float count = texelFetch(u_tail_count, texel, 0).r;
  if (count > 0.0 && tail.a > 0.0) {
    const float opacity = 1.0 - pow(max(1.0 - tail.a / count, 0.0), count);
    accumulated += transmittance * opacity * (tail.rgb / tail.a);
    transmittance *= 1.0 - opacity;
  }
  out_color = oit_finish(accumulated, transmittance);
}
