// adaptive_transparency's binding points, included by its C++ and
// its GLSL alike so that no number is copied by hand between the two
// (shaders/bindings.h: a technique's own start at OIT_FIRST_TECHNIQUE_*).
#ifndef OIT_ADAPTIVE_TRANSPARENCY_BINDINGS_H
#define OIT_ADAPTIVE_TRANSPARENCY_BINDINGS_H

#include "shaders/bindings.h"

// Storage buffer binding points.
#define ADAPTIVE_TRANSPARENCY_NODES_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define ADAPTIVE_TRANSPARENCY_COUNTS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 1)
#define ADAPTIVE_TRANSPARENCY_LOCKS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 2)

// Texture units.
#define ADAPTIVE_TRANSPARENCY_ACCUMULATION_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 0)

// Its parameters: shaders/pixel_slots.h (k: the nodes per pixel).

#endif
