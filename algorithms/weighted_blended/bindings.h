// weighted_blended's texture units and parameter block, included by its
// C++ and its GLSL alike so that no number is copied by hand between the two
// (shaders/bindings.h: a technique's own start at OIT_FIRST_TECHNIQUE_*).
#ifndef OIT_WEIGHTED_BLENDED_BINDINGS_H
#define OIT_WEIGHTED_BLENDED_BINDINGS_H

#include "shaders/bindings.h"
#include "shaders/std140.h"

// Texture units of the compose pass.
#define WEIGHTED_BLENDED_ACCUMULATION_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define WEIGHTED_BLENDED_REVEALAGE_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 1)

// Uniform block binding point of the frame's parameters (fill.frag).
#define WEIGHTED_BLENDED_PARAMS_BLOCK 0

OIT_STD140_BEGIN
struct WeightedBlendedParams {
  // View depths of the projection's near and far planes (eqs. 7-9 only).
  float near_view_depth, far_view_depth;
  float unused_0, unused_1;
};
OIT_STD140_END

#endif
