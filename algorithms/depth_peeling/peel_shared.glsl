// Shared by the depth-peeling shaders: texture units, the counter, and which
// fragments a layer key says are peeled already.
//
// A layer key is uvec2(view depth as float bits, submission index of the
// peeled fragment's triangle); a view depth of +infinity marks "nothing
// peeled here", -infinity "nothing peeled yet". Fragments are peeled in the
// order (view depth, submission index).
#include "algorithms/depth_peeling/bindings.h"

#define DEPTH_PEELING_EMPTY_DEPTH_BITS 0x7f800000u  // +infinity

#if defined(COUNT_SURVIVORS) && COUNT_SURVIVORS
layout(std430, binding = DEPTH_PEELING_COUNTER_BINDING) buffer DepthPeelingCounter {
  uint survivors_of_last_pass;  // un-peeled fragments seen by the capped last pass
};
#endif

bool not_peeled_yet(float depth, uint submitted, uvec2 previous) {
  const float previous_depth = uintBitsToFloat(previous.x);
  return depth > previous_depth || (depth == previous_depth && submitted > previous.y);
}
