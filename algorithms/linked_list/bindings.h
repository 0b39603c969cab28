// linked_list's binding points, units and uniform locations, included by its
// C++ and its GLSL alike so that no number is copied by hand between the two
// (shaders/bindings.h: a technique's own start at OIT_FIRST_TECHNIQUE_*).
#ifndef OIT_LINKED_LIST_BINDINGS_H
#define OIT_LINKED_LIST_BINDINGS_H

#include "shaders/bindings.h"

// Interleaved lists per pixel: the resolve walks them side by side so that
// their node loads overlap (README: 4 heads) and reads a pixel's heads as one uvec4.
#define LL_HEADS 4

// Storage buffer binding points.
#define LINKED_LIST_HEADS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define LINKED_LIST_NODES_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 1)
#define LINKED_LIST_COUNTERS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 2)
#define LINKED_LIST_LENGTHS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 3)
#define LINKED_LIST_CLASS_COMMANDS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 4)  // length_classes
#define LINKED_LIST_CLASS_TILES_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 5)

// The resolve's read-only views: the nodes on image unit 0 (imageLoad), heads
// and lengths on texture units 1 and 2 (texelFetch of buffer textures);
// tile.vert's view of the class lists on unit 3.
#define LINKED_LIST_NODES_IMAGE_UNIT 0
#define LINKED_LIST_HEADS_UNIT 1
#define LINKED_LIST_LENGTHS_UNIT 2
#define LINKED_LIST_CLASS_TILES_UNIT 3

// Uniform locations.
#define LINKED_LIST_CAPACITY_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 0)
#define LINKED_LIST_WIDTH_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 1)
#define LINKED_LIST_MAX_PER_PIXEL_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 2)
#define LINKED_LIST_SIZE_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 8)  // classify.comp, tile.vert: ivec2
#define LINKED_LIST_FIRST_TILE_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 9)

#endif
