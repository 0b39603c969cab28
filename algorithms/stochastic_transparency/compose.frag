#version 450 core
// Resolve and alpha correction (Enderton et al., section 3.4): the average
// of the accumulation's samples is sum T a (rgb, 1) with T estimated; the
// estimate decides only how the pixel's coverage is shared among its
// fragments, the coverage itself, 1 - prod (1 - a), is exact.
#include "shaders/compose.glsl"
#include "algorithms/stochastic_transparency/bindings.h"

layout(binding = STOCHASTIC_TRANSPARENCY_ACCUMULATION_UNIT) uniform sampler2DMS u_accumulation;
layout(binding = STOCHASTIC_TRANSPARENCY_TOTAL_TRANSMITTANCE_UNIT) uniform sampler2D u_total_transmittance;

layout(location = 0) out vec4 out_color;

void main() {
  const ivec2 texel = ivec2(gl_FragCoord.xy);
  vec4 accumulation = vec4(0.0);
  for (int s = 0; s < SAMPLES; ++s) accumulation += texelFetch(u_accumulation, texel, s);
  const float total_transmittance = texelFetch(u_total_transmittance, texel, 0).r;
  // The nearest fragment passes the depth test at every sample its triangle
  // covers, so the sum is 0 only where no fragment of alpha > 0 covers a
  // sample; then the coverage is 0 too (or only the pixel centre is covered).
  const vec3 average = accumulation.a > 0.0 ? accumulation.rgb / accumulation.a : vec3(0.0);
  out_color = oit_finish(average * (1.0 - total_transmittance), total_transmittance);
}
