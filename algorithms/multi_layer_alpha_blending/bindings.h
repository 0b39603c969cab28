// multi_layer_alpha_blending's binding points, included by its C++ and
// its GLSL alike so that no number is copied by hand between the two
// (shaders/bindings.h: a technique's own start at OIT_FIRST_TECHNIQUE_*).
#ifndef OIT_MULTI_LAYER_ALPHA_BLENDING_BINDINGS_H
#define OIT_MULTI_LAYER_ALPHA_BLENDING_BINDINGS_H

#include "shaders/bindings.h"

// Storage buffer binding points.
#define MULTI_LAYER_ALPHA_BLENDING_COLORS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define MULTI_LAYER_ALPHA_BLENDING_DEPTHS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 1)
#define MULTI_LAYER_ALPHA_BLENDING_COUNTS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 2)
#define MULTI_LAYER_ALPHA_BLENDING_LOCKS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 3)

// Its parameters: shaders/pixel_slots.h (k: the layers per pixel).

#endif
