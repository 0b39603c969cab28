// hybrid_transparency's binding points, included by its C++ and
// its GLSL alike so that no number is copied by hand between the two
// (shaders/bindings.h: a technique's own start at OIT_FIRST_TECHNIQUE_*).
#ifndef OIT_HYBRID_TRANSPARENCY_BINDINGS_H
#define OIT_HYBRID_TRANSPARENCY_BINDINGS_H

#include "shaders/bindings.h"

// Storage buffer binding points.
#define HYBRID_TRANSPARENCY_KEYS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define HYBRID_TRANSPARENCY_COLORS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 1)
#define HYBRID_TRANSPARENCY_COUNTERS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 2)

// Texture units.
#define HYBRID_TRANSPARENCY_TAIL_SUM_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define HYBRID_TRANSPARENCY_TAIL_COUNT_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 1)

// Its parameters: shaders/pixel_slots.h (k: the core slots per pixel).

#endif
