#version 450 core
// Accumulation pass: every fragment again, single-sampled. Its
// transmittance is estimated as the share of the pixel's samples whose
// stochastic depth is at or behind it (no fragment in front covered them):
// an unbiased estimate of prod over nearer fragments of (1 - alpha)
// (Enderton et al., section 3.2). Target 0 sums (T a rgb, T a) additively;
// target 1, on the first pass only, multiplies the exact total
// transmittance prod (1 - a) for the alpha correction (section 3.4).
#include "shaders/shading.glsl"

layout(binding = OIT_FIRST_TECHNIQUE_BINDING + 0) uniform sampler2DMS u_stochastic_depth;
layout(location = OIT_FIRST_TECHNIQUE_UNIFORM + 1) uniform bool u_first_pass;

layout(location = 0) out vec4 out_accumulation;
layout(location = 1) out vec4 out_total_alpha;

void main() {
  const vec4 color = oit_shade();
  const ivec2 texel = ivec2(gl_FragCoord.xy);
  const float depth = gl_FragCoord.z;
  int unoccluded = 0;
  for (int s = 0; s < SAMPLES; ++s) unoccluded += depth <= texelFetch(u_stochastic_depth, texel, s).r ? 1 : 0;
  const float transmittance = float(unoccluded) / float(SAMPLES);
  out_accumulation = transmittance * color.a * vec4(color.rgb, 1.0);
  out_total_alpha = vec4(u_first_pass ? color.a : 0.0);
}
