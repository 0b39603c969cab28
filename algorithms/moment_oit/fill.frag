#version 450 core
// Pass 1 of moment-based OIT: additive blending sums, per pixel, the
// absorbance b0 = sum A and the moments sum A * m(depth) over all fragments.
#include "shaders/shading.glsl"
#include "algorithms/moment_oit/moments.glsl"

layout(location = 0) out vec4 out_zeroth;
layout(location = 1) out vec4 out_moments_1_4;
#if MOMENT_COUNT > 4
layout(location = 2) out vec4 out_moments_5_8;
#endif

void main() {
  const float absorbance = moment_absorbance(oit_shade().a);
  float moments[MOMENT_COUNT];
  moment_vector(oit_view_depth(), moments);
  out_zeroth = vec4(absorbance);
  out_moments_1_4 = absorbance * vec4(moments[0], moments[1], moments[2], moments[3]);
#if MOMENT_COUNT == 6
  out_moments_5_8 = absorbance * vec4(moments[4], moments[5], 0.0, 0.0);
#elif MOMENT_COUNT == 8
  out_moments_5_8 = absorbance * vec4(moments[4], moments[5], moments[6], moments[7]);
#endif
}
