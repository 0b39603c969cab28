// dual_depth_peeling's binding points, texture units and uniform locations,
// included by its C++ and its GLSL alike so that no number is copied by hand
// between the two (shaders/bindings.h: a technique's own start at
// OIT_FIRST_TECHNIQUE_*).
#ifndef OIT_DUAL_DEPTH_PEELING_BINDINGS_H
#define OIT_DUAL_DEPTH_PEELING_BINDINGS_H

#include "shaders/bindings.h"

// tie_break=submission (dual_shared.glsl). Storage buffer: the capped last
// pass's count of fragments left inside the range.
#define DUAL_PEELING_COUNTER_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define DUAL_PEELING_RANGE_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define DUAL_PEELING_FRONT_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define DUAL_PEELING_BACK_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 1)

// tie_break=triangle_id (by_id_shared.glsl).
#define DUAL_ID_KEYS_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define DUAL_ID_NEXT_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 1)
#define DUAL_ID_SELECT_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 2)
#define DUAL_ID_COUNT_BACK_UNIFORM (OIT_FIRST_TECHNIQUE_UNIFORM + 0)  // bool u_count_back

#endif
