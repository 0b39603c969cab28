// weighted_blended's texture units and uniform locations, included by its
// C++ and its GLSL alike so that no number is copied by hand between the two
// (shaders/bindings.h: a technique's own start at OIT_FIRST_TECHNIQUE_*).
#ifndef OIT_WEIGHTED_BLENDED_BINDINGS_H
#define OIT_WEIGHTED_BLENDED_BINDINGS_H

#include "shaders/bindings.h"

// Texture units of the compose pass.
#define WEIGHTED_BLENDED_ACCUMULATION_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define WEIGHTED_BLENDED_REVEALAGE_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 1)

// Uniform locations.
#define WEIGHTED_BLENDED_NEAR_FAR_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 0)  // vec2 u_near_far

#endif
