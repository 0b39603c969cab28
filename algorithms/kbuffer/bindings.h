// kbuffer's binding points and uniform locations, included by its C++ and
// its GLSL alike so that no number is copied by hand between the two
// (shaders/bindings.h: a technique's own start at OIT_FIRST_TECHNIQUE_*).
#ifndef OIT_KBUFFER_BINDINGS_H
#define OIT_KBUFFER_BINDINGS_H

#include "shaders/bindings.h"

// Storage buffer binding points.
#define KBUFFER_KEYS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define KBUFFER_OWNERS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 1)
#define KBUFFER_COLORS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 2)
#define KBUFFER_COUNTERS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 3)

// Texture units.
#define KBUFFER_TAIL_ACCUMULATION_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define KBUFFER_TAIL_REVEALAGE_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 1)

// The frame's parameters (width, k) are the shared block of techniques with
// k slots per pixel: PixelSlotsParams (shaders/pixel_slots.h). k is not the
// define K: with k=auto one program (K = the next power of two) serves every
// k up to K, and loops bounded by a uniform are not unrolled; K only sizes
// compose's local arrays.

#endif
