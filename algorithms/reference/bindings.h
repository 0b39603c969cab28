// reference's binding points and uniform locations, included by its C++ and
// its GLSL alike so that no number is copied by hand between the two
// (shaders/bindings.h: a technique's own start at OIT_FIRST_TECHNIQUE_*).
#ifndef OIT_REFERENCE_BINDINGS_H
#define OIT_REFERENCE_BINDINGS_H

#include "shaders/bindings.h"

// Storage buffer binding points.
#define REFERENCE_HEADS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define REFERENCE_NODES_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 1)
#define REFERENCE_COUNTER_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 2)
#define REFERENCE_LENGTHS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 3)

// Uniform locations.
#define REFERENCE_CAPACITY_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 0)
#define REFERENCE_WIDTH_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 1)

#endif
