// bucketed_kbuffer's binding points, texture units and uniform locations,
// included by its C++ and its GLSL alike so that no number is copied by hand
// between the two (shaders/bindings.h: a technique's own start at
// OIT_FIRST_TECHNIQUE_*).
#ifndef OIT_BUCKETED_KBUFFER_BINDINGS_H
#define OIT_BUCKETED_KBUFFER_BINDINGS_H

#include "shaders/bindings.h"

// Storage buffer binding points (bkb_common.glsl), consecutive: the C++ binds
// its ten buffers in this order from BKB_Z_BINDING.
#define BKB_Z_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define BKB_BUCKETS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 1)
#define BKB_COLORS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 2)
#define BKB_NORMALS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 3)
#define BKB_FEATURES_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 4)
#define BKB_COUNTERS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 5)
#define BKB_LINKS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 6)
#define BKB_EXPECTED_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 7)
#define BKB_ESTIMATED_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 8)
#define BKB_TRUTH_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 9)
#define BKB_BUFFER_COUNT 10

// Texture units of the stylize pass.
#define BKB_COLOR_TRANSFER_UNIT 0
#define BKB_OPACITY_TRANSFER_UNIT 1

// Uniform locations.
#define BKB_WIDTH_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 0)
#define BKB_HEIGHT_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 1)
#define BKB_DEPTH_NEAR_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 2)
#define BKB_DEPTH_FAR_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 3)
#define BKB_INVERSE_PROJECTION_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 4)  // neighbors.frag
#define BKB_CURVATURE_SCALE_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 5)     // neighbors.frag

#endif
