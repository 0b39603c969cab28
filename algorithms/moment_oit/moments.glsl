// Moment-based OIT (Münstermann, Krumpen, Klein & Peters 2018): what both
// geometry passes share. Every fragment's absorbance A = -ln(1 - alpha)
// is an atom of a distribution over (warped) depth; pass 1 sums A (the
// zeroth moment b0) and A times the moment vector of the fragment's depth;
// pass 2 reconstructs, per fragment, the absorbance in front of it from
// those moments (the canonical representation through the fragment's depth)
// and weights its colour with the resulting transmittance.
//
// MOMENT_COUNT (4, 6, 8) real numbers per pixel besides b0:
//   TRIGONOMETRIC == 0: power moments b_k = sum A d^k, k = 1..MOMENT_COUNT,
//   TRIGONOMETRIC == 1: MOMENT_COUNT / 2 trigonometric moments
//                        sum A (cos k theta, sin k theta), k = 1..MOMENT_COUNT / 2.
// Either way the moment matrix has order MOMENT_ORDER + 1 and the kernel
// polynomial degree MOMENT_ORDER.
#include "shaders/bindings.h"
#include "algorithms/moment_oit/bindings.h"

#define MOMENT_ORDER (MOMENT_COUNT / 2)
#define MOMENT_PI 3.14159265358979

// Warp: d = clamp(2 (f(z) - f(near)) u_depth_warp.y - 1, -1, 1), f = ln for a
// perspective projection, identity for an orthographic one;
// u_depth_warp = (f(near), 1 / (f(far) - f(near))).
layout(location = MOMENT_OIT_DEPTH_WARP_LOCATION) uniform vec2 u_depth_warp;
layout(location = MOMENT_OIT_LOG_DEPTH_LOCATION) uniform bool u_log_depth;
// Trigonometric moments: the angle left free between the far and the near
// end of the depth range (radians), so that they do not wrap onto each other.
layout(location = MOMENT_OIT_WRAPPING_ZONE_LOCATION) uniform float u_wrapping_zone;

// The paper clamps a fragment's absorbance so that alpha = 1 stays finite
// (and half-float sums stay far from overflow): e^-10 = 4.5e-5 of the light
// still passes an opaque fragment.
const float kMaxAbsorbance = 10.0;

float moment_absorbance(float alpha) { return min(-log(max(1.0 - alpha, 1e-30)), kMaxAbsorbance); }

float moment_warped_depth(float view_depth) {
  const float f = u_log_depth ? log(max(view_depth, 1e-30)) : view_depth;
  return clamp(2.0 * (f - u_depth_warp.x) * u_depth_warp.y - 1.0, -1.0, 1.0);
}

// The angle of a warped depth: [-1, 1] onto [-pi + w/2, pi - w/2]; the
// wrapping zone of width w is centred on pi = -pi.
float moment_angle(float warped_depth) {
  return -MOMENT_PI + 0.5 * u_wrapping_zone + 0.5 * (warped_depth + 1.0) * (2.0 * MOMENT_PI - u_wrapping_zone);
}

// The moment vector (without the zeroth) of one unit atom at this view depth.
void moment_vector(float view_depth, out float moments[MOMENT_COUNT]) {
  const float d = moment_warped_depth(view_depth);
#if TRIGONOMETRIC
  const float theta = moment_angle(d);
  for (int k = 0; k < MOMENT_ORDER; ++k) {
    moments[2 * k] = cos(float(k + 1) * theta);
    moments[2 * k + 1] = sin(float(k + 1) * theta);
  }
#else
  float power = 1.0;
  for (int k = 0; k < MOMENT_COUNT; ++k) {
    power *= d;
    moments[k] = power;
  }
#endif
}
