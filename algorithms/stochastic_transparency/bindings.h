// stochastic_transparency's texture units and uniform locations, included by
// its C++ and its GLSL alike so that no number is copied by hand between the
// two (shaders/bindings.h: a technique's own start at OIT_FIRST_TECHNIQUE_*).
#ifndef OIT_STOCHASTIC_TRANSPARENCY_BINDINGS_H
#define OIT_STOCHASTIC_TRANSPARENCY_BINDINGS_H

#include "shaders/bindings.h"

// Texture units of the compose pass.
#define STOCHASTIC_TRANSPARENCY_ACCUMULATION_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 1)
#define STOCHASTIC_TRANSPARENCY_TOTAL_TRANSMITTANCE_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 2)

// Uniform locations.
#define STOCHASTIC_TRANSPARENCY_SEED_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 0)  // uint u_seed of depth.frag

#endif
