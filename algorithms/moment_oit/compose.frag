#version 450 core
// Composite of moment-based OIT (the paper's section 3.3): the accumulated
// colours are renormalised so that together they cover exactly
// 1 - exp(-b0), the pixel's true total opacity; the background shows
// through exp(-b0). The reconstruction thus only decides how the covered
// share is split between the fragments.
#include "shaders/compose.glsl"
#include "algorithms/moment_oit/bindings.h"

layout(binding = MOMENT_OIT_ZEROTH_UNIT) uniform sampler2D u_zeroth;
layout(binding = MOMENT_OIT_ACCUMULATION_UNIT) uniform sampler2D u_accumulation;

layout(location = 0) out vec4 out_color;

void main() {
  const ivec2 texel = ivec2(gl_FragCoord.xy);
  const float total_transmittance = exp(-texelFetch(u_zeroth, texel, 0).r);
  const vec4 accumulation = texelFetch(u_accumulation, texel, 0);
  // A weighted average of colours in [0, 1]; none accumulated (every
  // fragment hidden behind an underflowed transmittance) leaves black.
  const vec3 average = accumulation.a > 0.0 ? accumulation.rgb / accumulation.a : vec3(0.0);
  out_color = oit_finish(average * (1.0 - total_transmittance), total_transmittance);
}
