// linearized_fragment_buffer's binding points, units, parameter blocks and uniform location,
// included by its C++ and its GLSL alike so that no number is copied by hand
// between the two (shaders/bindings.h: a technique's own start at
// OIT_FIRST_TECHNIQUE_*). The resolve is drawn by linked_list's length
// classes (tile.vert, classify.comp), whose numbers it shares.
#ifndef OIT_LINEARIZED_FRAGMENT_BUFFER_BINDINGS_H
#define OIT_LINEARIZED_FRAGMENT_BUFFER_BINDINGS_H

#include "shaders/bindings.h"
#include "algorithms/linked_list/bindings.h"

// Storage buffer binding points: the fill's and the resolve's, and the prefix sum's (a pass of its own).
#define LFB_KEYS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 2)        // the fill's 64-bit keys (LFB_KEY64)
#define LFB_MISMATCHED_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 6)  // the resolve's range check
#define LFB_PREFIX_SUM_VALUES_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define LFB_PREFIX_SUM_SUMS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 1)
#define LFB_PREFIX_SUM_LENGTHS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 3)  // PS_FROM_COUNTS: uint(count) per pixel
#define LFB_PREFIX_SUM_LONGEST_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 4)  // PS_FROM_COUNTS: the largest count

// The nodes on image unit 0, the fill's cursors on image unit 2; the offsets
// on texture unit 1 and, in the resolve, the lengths on the unit where
// linked_list's classify.comp reads them; the prefix sum's counts on texture
// unit 0; the scene's flat colours (flat_color_nodes) on unit 4 (unit 3 holds
// tile.vert's class tiles); the fill's final cursors, which the resolve
// checks, on unit 5.
#define LFB_NODES_IMAGE_UNIT 0
#define LFB_CURSORS_IMAGE_UNIT 2
#define LFB_OFFSETS_UNIT 1
#define LFB_LENGTHS_UNIT LINKED_LIST_LENGTHS_UNIT
#define LFB_PREFIX_SUM_COUNTS_UNIT 0
#define LFB_FLAT_COLORS_UNIT (LINKED_LIST_CLASS_TILES_UNIT + 1)
#define LFB_FINAL_CURSORS_UNIT (LINKED_LIST_CLASS_TILES_UNIT + 2)

// Uniform block binding points: the fill's and the resolve's parameters,
// and the prefix sum's; beside LINKED_LIST_CLASSES_PARAMS_BLOCK, which the
// length classes bind for the resolve.
#define LFB_PARAMS_BLOCK 0
#define LFB_PREFIX_SUM_PARAMS_BLOCK 2

OIT_STD140_BEGIN
struct LfbParams {
  int width;  // the frame's width in pixels
  uint unused_0, unused_1, unused_2;
};
struct PrefixSumParams {
  int width;    // of the counts texture (PS_FROM_COUNTS)
  uint pixels;  // counts in it
  uint unused_0, unused_1;
};
OIT_STD140_END

// The values a prefix sum dispatch scans, a uniform of its own: it differs
// between the dispatches of one scan (one per level).
#define LFB_PREFIX_SUM_COUNT_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 0)

#endif
