#version 450 core
// The single geometry pass of weighted blended OIT (McGuire & Bavoil 2013).
// Target 0 (additive, ONE/ONE):     sum of w * premultiplied rgb, sum of w * alpha.
// Target 1 (ZERO, ONE_MINUS_SRC_COLOR): revealage = product of (1 - alpha).
// The paper's weights include the alpha factor: w = alpha * f(depth).
#include "shaders/shading.glsl"
#include "algorithms/weighted_blended/bindings.h"

layout(std140, binding = WEIGHTED_BLENDED_PARAMS_BLOCK) uniform WeightedBlendedBlock { WeightedBlendedParams wb; };

layout(location = 0) out vec4 out_accumulation;
layout(location = 1) out vec4 out_revealage;

// Eqs. 7-9 were tuned for view depths in [0.1, 500] (the paper's units).
// Scenes here come in any scale, so the view depth is mapped linearly from
// [near, far] of the projection onto that range first.
float paper_depth(float view_depth) {
  const float t = clamp((view_depth - wb.near_view_depth) / (wb.far_view_depth - wb.near_view_depth), 0.0, 1.0);
  return mix(0.1, 500.0, t);
}

float depth_weight(float view_depth) {
#if WEIGHT_EQUATION == 10
  // Eq. 10: window-space depth d in [0, 1] (gl_FragCoord.z), the projection's own near/far.
  const float d = 1.0 - gl_FragCoord.z;
  return max(1e-2, 3e3 * d * d * d);
#else
  const float z = paper_depth(view_depth);
#if WEIGHT_EQUATION == 7
  const float a = z / 5.0, b = z / 200.0;
  return clamp(10.0 / (1e-5 + a * a + b * b * b * b * b * b), 1e-2, 3e3);
#elif WEIGHT_EQUATION == 8
  const float a = z / 10.0, b = z / 200.0;
  return clamp(10.0 / (1e-5 + a * a * a + b * b * b * b * b * b), 1e-2, 3e3);
#elif WEIGHT_EQUATION == 9
  const float a = z / 200.0;
  return clamp(0.03 / (1e-5 + a * a * a * a), 1e-2, 3e3);
#else
#error "WEIGHT_EQUATION must be 7, 8, 9 or 10"
#endif
#endif
}

void main() {
  const vec4 color = oit_shade();
  const float weight = color.a * depth_weight(oit_view_depth());
  out_accumulation = vec4(color.rgb * color.a, color.a) * weight;
  out_revealage = vec4(color.a);
}
