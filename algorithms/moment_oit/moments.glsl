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

layout(std140, binding = MOMENT_OIT_PARAMS_BLOCK) uniform MomentOitBlock { MomentOitParams moment_params; };

// The paper clamps a fragment's absorbance so that alpha = 1 stays finite
// (and half-float sums stay far from overflow): e^-10 = 4.5e-5 of the light
// still passes an opaque fragment.
const float kMaxAbsorbance = 10.0;

float moment_absorbance(float alpha) { return min(-log(max(1.0 - alpha, 1e-30)), kMaxAbsorbance); }

float moment_warped_depth(float view_depth) {
  const float f = moment_params.log_depth != 0u ? log(max(view_depth, 1e-30)) : view_depth;
  return clamp(2.0 * (f - moment_params.warp_offset) * moment_params.warp_scale - 1.0, -1.0, 1.0);
}

// The angle of a warped depth: [-1, 1] onto [-pi + w/2, pi - w/2]; the
// wrapping zone of width w is centred on pi = -pi.
float moment_angle(float warped_depth) {
  const float zone = moment_params.wrapping_zone;
  return -MOMENT_PI + 0.5 * zone + 0.5 * (warped_depth + 1.0) * (2.0 * MOMENT_PI - zone);
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
