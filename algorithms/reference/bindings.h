// reference's binding points and parameter block, included by its C++ and
// its GLSL alike so that no number is copied by hand between the two
// (shaders/bindings.h: a technique's own start at OIT_FIRST_TECHNIQUE_*).
#ifndef OIT_REFERENCE_BINDINGS_H
#define OIT_REFERENCE_BINDINGS_H

#include "shaders/bindings.h"
#include "shaders/std140.h"

// Storage buffer binding points.
#define REFERENCE_HEADS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define REFERENCE_NODES_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 1)
#define REFERENCE_COUNTER_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 2)
#define REFERENCE_LENGTHS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 3)

// Uniform block binding point of the fill's and the resolve's parameters.
#define REFERENCE_PARAMS_BLOCK 0

OIT_STD140_BEGIN
struct ReferenceParams {
  uint capacity;  // nodes in the pool; the fill counts, but does not store, the ones beyond
  int width;      // the frame's width in pixels
  uint unused_0, unused_1;
};
OIT_STD140_END

#endif
