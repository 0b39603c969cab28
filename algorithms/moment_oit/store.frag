#version 450 core
// Pass 2 of moment-based OIT: every fragment again, its colour weighted by
// the transmittance exp(-b0 * front fraction) reconstructed at its depth,
// summed additively: (sum T a rgb, sum T a).
#include "shaders/shading.glsl"
#include "algorithms/moment_oit/reconstruction.glsl"
#include "algorithms/moment_oit/bindings.h"

layout(binding = MOMENT_OIT_ZEROTH_UNIT) uniform sampler2D u_zeroth;
layout(binding = MOMENT_OIT_MOMENTS_1_4_UNIT) uniform sampler2D u_moments_1_4;
#if MOMENT_COUNT > 4
layout(binding = MOMENT_OIT_MOMENTS_5_8_UNIT) uniform sampler2D u_moments_5_8;
#endif

layout(location = 0) out vec4 out_accumulation;

void main() {
  const vec4 color = oit_shade();
  const ivec2 texel = ivec2(gl_FragCoord.xy);
  const float b0 = texelFetch(u_zeroth, texel, 0).r;
  float transmittance = 1.0;
  if (b0 > 0.0) {
    const vec4 low = texelFetch(u_moments_1_4, texel, 0) / b0;
    float normalized[MOMENT_COUNT];
    normalized[0] = low.x;
    normalized[1] = low.y;
    normalized[2] = low.z;
    normalized[3] = low.w;
#if MOMENT_COUNT > 4
    const vec4 high = texelFetch(u_moments_5_8, texel, 0) / b0;
    normalized[4] = high.x;
    normalized[5] = high.y;
#endif
#if MOMENT_COUNT > 6
    normalized[6] = high.z;
    normalized[7] = high.w;
#endif
    transmittance = exp(-b0 * front_fraction(normalized, moment_warped_depth(oit_view_depth())));
  }
  out_accumulation = transmittance * color.a * vec4(color.rgb, 1.0);
}
