// depth_peeling's binding points and texture units, included by its C++ and
// its GLSL alike so that no number is copied by hand between the two
// (shaders/bindings.h: a technique's own start at OIT_FIRST_TECHNIQUE_*).
#ifndef OIT_DEPTH_PEELING_BINDINGS_H
#define OIT_DEPTH_PEELING_BINDINGS_H

#include "shaders/bindings.h"

// tie_break=submission (peel_shared.glsl). Storage buffer: the capped last
// pass's count of fragments it did not peel.
#define DEPTH_PEELING_COUNTER_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 0)
// Geometry pass: the key of the layer peeled last.
#define DEPTH_PEELING_PREVIOUS_KEYS_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 0)
// Blend and compose passes.
#define DEPTH_PEELING_LAYER_COLOR_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define DEPTH_PEELING_LAYER_KEYS_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 1)
#define DEPTH_PEELING_ACCUMULATION_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 0)

// tie_break=triangle_id (by_id_shared.glsl): the per-pixel state and the GL_MIN selection.
#define DP_ID_STATE_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define DP_ID_SELECT_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 1)

#endif
