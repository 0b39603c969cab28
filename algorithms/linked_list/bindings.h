// linked_list's binding points, units, parameter blocks and uniform location, included by its
// C++ and its GLSL alike so that no number is copied by hand between the two
// (shaders/bindings.h: a technique's own start at OIT_FIRST_TECHNIQUE_*).
#ifndef OIT_LINKED_LIST_BINDINGS_H
#define OIT_LINKED_LIST_BINDINGS_H

#include "shaders/bindings.h"
#include "shaders/std140.h"

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

// Uniform block binding points: the fill's and the resolve's parameters
// (nodes.glsl), and the length classes' (classify.comp, tile.vert), which
// linearized_fragment_buffer draws with its own block bound beside them.
#define LINKED_LIST_PARAMS_BLOCK 0
#define LINKED_LIST_CLASSES_PARAMS_BLOCK 1

OIT_STD140_BEGIN
struct LinkedListParams {
  uint capacity;       // nodes in the pool; the fill counts, but does not store, the ones beyond
  int width;           // the frame's width in pixels
  uint max_per_pixel;  // longer lists count the rest as dropped (fill.frag)
  uint unused;
};
struct LengthClassesParams {
  int width, height;  // the frame's pixels
  uint unused_0, unused_1;
};
OIT_STD140_END

// tile.vert's first tile of a class draw, a uniform of its own: it differs
// between the draws of one frame.
#define LINKED_LIST_FIRST_TILE_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 9)

#endif
