#version 450 core
// Compose with the alpha correction (Enderton et al., section 3.4): the
// stochastic estimate decides only how the pixel's coverage is shared among
// its fragments; the coverage itself, 1 - prod (1 - a), is exact.
#include "shaders/compose.glsl"

layout(binding = OIT_FIRST_TECHNIQUE_BINDING + 1) uniform sampler2D u_accumulation;
layout(binding = OIT_FIRST_TECHNIQUE_BINDING + 2) uniform sampler2D u_total_transmittance;

layout(location = 0) out vec4 out_color;

void main() {
  const ivec2 texel = ivec2(gl_FragCoord.xy);
  const vec4 accumulation = texelFetch(u_accumulation, texel, 0);
  const float total_transmittance = texelFetch(u_total_transmittance, texel, 0).r;
  // The nearest fragment's estimate is always 1 (nothing lies in front of
  // it), so the sum is 0 only where every fragment had alpha 0.
  const vec3 average = accumulation.a > 0.0 ? accumulation.rgb / accumulation.a : vec3(0.0);
  out_color = oit_finish(average * (1.0 - total_transmittance), total_transmittance);
}
