// Shared by the dual-depth-peeling shaders. A depth range is stored as
// vec2(-nearest, farthest) so that GL_MAX blending computes both the minimum
// and the maximum depth at once; vec2(-FLT_MAX) is the empty range (and the
// identity of MAX), under which every fragment counts as peeled already.
#include "algorithms/dual_depth_peeling/bindings.h"

#define DUAL_PEELING_EMPTY_RANGE vec2(-3.402823466e38)

// COUNT_LEFT_UNPEELED is 1 only in the variant used for the last pass
// max_passes allows: fragments still strictly inside the range after it are
// never composited, so it counts them. (An atomic slows a pass down on Mesa
// llvmpipe even where it never runs, hence a separate program.) Include
// shaders/subgroup_atomics.glsl first where the count is taken.
#if defined(COUNT_LEFT_UNPEELED) && COUNT_LEFT_UNPEELED
layout(std430, binding = DUAL_PEELING_COUNTER_BINDING) buffer DualDepthPeelingCounter {
  uint left_unpeeled;
};
#define DUAL_PEELING_COUNT_LEFT_UNPEELED() OIT_ATOMIC_COUNT(left_unpeeled)
#else
#define DUAL_PEELING_COUNT_LEFT_UNPEELED()
#endif
