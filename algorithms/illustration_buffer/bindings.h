// illustration_buffer's binding points, units, uniform locations and sentinels, included
// by its C++ and its GLSL alike so that no number is copied by hand between
// the two (shaders/bindings.h: a technique's own start at OIT_FIRST_TECHNIQUE_*).
#ifndef OIT_ILLUSTRATION_BUFFER_BINDINGS_H
#define OIT_ILLUSTRATION_BUFFER_BINDINGS_H

#include "shaders/bindings.h"

// Sentinels the shaders write and the C++ clears with or reads back (accuracy.h).
#define IB_NIL 0xffffffffu        // end of a list
#define IB_NONE 0xffffffffu       // no geodesic neighbour in that direction
#define IB_OFF_IMAGE 0xfffffffeu  // the adjacent pixel lies outside the image

// Storage buffer binding points (ib_storage.glsl unless noted).
#define IB_HEAD_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define IB_COUNT_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 1)
#define IB_NEXT_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 2)
#define IB_DATA_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 3)   // fragData: fill records, later both field ranges
#define IB_DATA2_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 4)  // fragData2: sorted search records
#define IB_COUNTERS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 5)
#define IB_TRUTH_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 6)       // fill.frag, measure_accuracy
#define IB_FIELDS_IN_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 7)   // fields.glsl
#define IB_FIELDS_OUT_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 8)  // fields.glsl
#define IB_DATA3_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 9)       // fragData3: sorted shade records and links
#define IB_STAMPS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 10)     // worklist.glsl (skip_converged)
#define IB_WORK_OUT_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 11)
#define IB_PIXEL_UPDATES_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 12)
#define IB_WORK_NEXT_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 13)  // stylize_diffuse.comp, IB_WORKLIST
#define IB_SEEDS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 14)      // stylize_init.comp, IB_TRACK
#define IB_SWEEP_CHANGED_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 15)  // stylize_init.comp (IB_SEED_FLAG), stylize_diffuse.comp (IB_CHECK)
#define IB_DISTANCES_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 16)  // sweep_distances.glsl

// Texture units of the read-only buffer-texture views. The per-fragment
// passes' (views.glsl) and the listed diffusion steps' (stylize_diffuse.comp):
#define IB_SEARCH_UNIT 0
#define IB_FIELDS_UNIT 1
#define IB_SHADE_UNIT 2
#define IB_WORK_UNIT 3
#define IB_HEAD_UNIT 4
#define IB_COUNT_UNIT 5
#define IB_SEEDS_UNIT 6  // stylize_seed_queue.comp
#define IB_LISTED_PIXELS_UNIT 7  // pixel_dispatch.glsl (IB_LISTED): sort.comp, neighbors_triangle_index.comp
#define IB_DISTANCES_UNIT 8      // sweep_distances.glsl: the sweeps' hop distances
#define IB_FIELD_TABLE_UNIT 9    // sweep_distances.glsl: beta and gamma by hop distance
// The sort's (sort.comp), a program of its own: fill records and the triangle table.
#define IB_FRAGMENT_UNIT 0
#define IB_SORT_TRIANGLES_UNIT 1  // neighbors=triangle_index
#define IB_OFFSETS_UNIT 2          // storage=linearized: the fill's per-pixel ranges; arrays: the fill's counts
// 3: free
#define IB_FLAT_COLORS_UNIT 4      // flat_color_records: the scene's colour per stable triangle id
// Image units (fill.frag; the cursors with storage=linearized or arrays and fill=atomic).
#define IB_CURSORS_IMAGE_UNIT 0

// Uniform locations. u_width / u_height are declared by ib_storage.glsl for
// every program, and each program uses a subset (the C++ asks uniform_active).
#define IB_WIDTH_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 0)
#define IB_HEIGHT_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 1)
#define IB_CAPACITY_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 2)       // fill.frag
#define IB_MAX_PER_PIXEL_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 3)  // fill.frag, sort.comp (IB_DYNAMIC)
#define IB_FRAGMENTS_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 4)      // per_fragment.glsl
#define IB_WEIGHT_Z_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 5)       // neighbors.comp, IB_HEURISTIC
#define IB_WEIGHT_N_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 6)
#define IB_INVERSE_RADIUS_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 7)
#define IB_LISTED_PIXELS_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 8)  // pixel_dispatch.glsl, IB_LISTED
#define IB_USE_BETA_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 9)  // stylize_init.comp
#define IB_USE_GAMMA_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 10)
#define IB_LAMBDA_ALPHA_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 11)  // stylize_diffuse.comp
#define IB_LAMBDA_BETA_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 12)
#define IB_LAMBDA_GAMMA_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 13)
#define IB_SLOTS_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 14)  // fill.frag, sort.comp (IB_ARRAYS): slots per pixel
#define IB_PROFILE_P_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 15)  // compose.frag, IB_MODULATE
#define IB_NEXT_STEP_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 16)  // worklist.glsl
#define IB_TOLERANCE_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 17)  // stylize_diffuse.comp, IB_WORKLIST
#define IB_NORMAL_VARIATION_SCALE_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 18)  // fill.frag, IB_NORMAL_VARIATION
#define IB_SWEEP_DIRECTION_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 19)  // stylize_diffuse.comp, IB_SWEEP
#define IB_TABLE_SIZE_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 20)      // stylize_diffuse.comp, IB_CHECK
#define IB_DISTANCE_CUTOFF_LOCATION (OIT_FIRST_TECHNIQUE_UNIFORM + 21) // stylize_diffuse.comp, IB_SWEEP and IB_CHECK

#endif
