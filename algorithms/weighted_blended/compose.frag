#version 450 core
// Compose of weighted blended OIT: the weighted average colour covers
// (1 - revealage) of the pixel; the background shows through the rest.
#include "shaders/compose.glsl"
#include "algorithms/weighted_blended/bindings.h"

layout(binding = WEIGHTED_BLENDED_ACCUMULATION_UNIT) uniform sampler2D u_accumulation;
layout(binding = WEIGHTED_BLENDED_REVEALAGE_UNIT) uniform sampler2D u_revealage;

layout(location = 0) out vec4 out_color;

void main() {
  const ivec2 texel = ivec2(gl_FragCoord.xy);
  const vec4 accumulation = texelFetch(u_accumulation, texel, 0);
  const float revealage = texelFetch(u_revealage, texel, 0).r;
  // The paper's overflow guard (a half-float sum can reach infinity): it
  // sets rgb to alpha, i.e. an average of 1. Written as that average
  // directly, so an infinite alpha gives white instead of inf/inf = NaN.
  const vec4 magnitude = abs(accumulation);
  const bool overflow = isinf(max(max(magnitude.r, magnitude.g), max(magnitude.b, magnitude.a)));
  const vec3 average = overflow ? vec3(1.0) : accumulation.rgb / max(accumulation.a, 1e-5);
  out_color = oit_finish(average * (1.0 - revealage), revealage);
}
