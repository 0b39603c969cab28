#version 450 core
// After a tie_break=triangle_id peel pass: the new per-pixel state from the
// old one and the pass's GL_MIN reductions. A candidate at the selected depth
// keeps the depth and `next`; one at `next` moves the selected depth there and
// takes the nearest depth beyond as the new `next`. Pixels without a
// candidate are finished: discarded, they keep the "nothing here" state the
// host cleared, and the occlusion query around this pass counts exactly the
// fragments selected (each composited by the next pass). After pass 1, which
// only reduces the nearest depth, that depth becomes the first `next`.
#include "algorithms/depth_peeling/by_id_shared.glsl"

layout(binding = DP_ID_STATE_UNIT) uniform usampler2D u_state;
layout(binding = DP_ID_SELECT_UNIT) uniform sampler2D u_select;

layout(location = 0) out uvec4 out_state;

void main() {
  const ivec2 pixel = ivec2(gl_FragCoord.xy);
  const vec2 select = texelFetch(u_select, pixel, 0).xy;
  const uvec4 state = texelFetch(u_state, pixel, 0);
  const uint candidate = floatBitsToUint(select.x);
  if (state.z == DP_ID_NEAREST_NOT_KNOWN_BITS) {
    out_state = uvec4(state.xy, floatBitsToUint(select.y), 0u);  // pass 1: the nearest depth is next
  } else if (candidate == DP_ID_NO_CANDIDATE_BITS) {
    discard;
  } else if (candidate < DP_ID_BAND_AT_NEXT) {
    out_state = uvec4(state.x, candidate - DP_ID_BAND_AT_SELECTED, state.z, 0u);
  } else {
    out_state = uvec4(state.z, candidate - DP_ID_BAND_AT_NEXT, floatBitsToUint(select.y), 0u);
  }
}
