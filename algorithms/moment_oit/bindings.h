// moment_oit's binding points and parameter block, included by its C++ and
// its GLSL alike so that no number is copied by hand between the two
// (shaders/bindings.h: a technique's own start at OIT_FIRST_TECHNIQUE_*).
#ifndef OIT_MOMENT_OIT_BINDINGS_H
#define OIT_MOMENT_OIT_BINDINGS_H

#include "shaders/bindings.h"
#include "shaders/std140.h"

// Texture units.
#define MOMENT_OIT_ZEROTH_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define MOMENT_OIT_MOMENTS_1_4_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 1)
#define MOMENT_OIT_MOMENTS_5_8_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 2)
#define MOMENT_OIT_ACCUMULATION_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 3)

// Uniform block binding point of the parameters of both geometry passes.
#define MOMENT_OIT_PARAMS_BLOCK 0

OIT_STD140_BEGIN
struct MomentOitParams {
  // Warp: d = clamp(2 (f(z) - warp_offset) warp_scale - 1, -1, 1), f = ln for
  // a perspective projection (log_depth 1), identity for an orthographic
  // one; warp_offset = f(near), warp_scale = 1 / (f(far) - f(near)).
  float warp_offset, warp_scale;
  uint log_depth;
  // Trigonometric moments: the angle left free between the far and the near
  // end of the depth range (radians), so that they do not wrap onto each other.
  float wrapping_zone;
  float moment_bias, overestimation;  // the paper's alpha and beta (reconstruction.glsl)
  float unused_0, unused_1;
};
OIT_STD140_END

#endif
