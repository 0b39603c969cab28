#version 450 core
// After a tie_break=triangle_id dual peeling pass: the new per-pixel state
// from the old one and the pass's GL_MIN reductions. On each side a candidate
// at the selected depth keeps that depth and the next one; a candidate at the
// next depth moves the selected depth there and takes the reduced depth
// beyond as the new next. Pixels without a candidate (then neither side has
// one) are finished: discarded, they keep the "nothing here" keys the host
// cleared. The host draws this twice inside one occlusion query: once
// surviving where a front fragment is selected, once (u_count_back) where a
// back fragment distinct from it is, so the query counts exactly the
// fragments the next pass composites. Both draws write the same state.
#include "algorithms/dual_depth_peeling/by_id_shared.glsl"

layout(binding = DUAL_ID_KEYS_UNIT) uniform usampler2D u_selected_keys;
layout(binding = DUAL_ID_NEXT_UNIT) uniform sampler2D u_next_depths;
layout(binding = DUAL_ID_SELECT_UNIT) uniform sampler2D u_select;
layout(location = DUAL_ID_COUNT_BACK_UNIFORM) uniform bool u_count_back;

layout(location = 0) out uvec4 out_selected_keys;
layout(location = 1) out vec2 out_next_depths;

void main() {
  const ivec2 pixel = ivec2(gl_FragCoord.xy);
  const vec4 select = texelFetch(u_select, pixel, 0);
  const uint front = floatBitsToUint(select.x), back = floatBitsToUint(select.z);
  if (front == DUAL_ID_NO_CANDIDATE_BITS) discard;
  const uvec4 selected = texelFetch(u_selected_keys, pixel, 0);
  const vec2 next = texelFetch(u_next_depths, pixel, 0).xy;  // -front next, back next
  uvec4 keys;
  vec2 next_depths;
  if (front < DUAL_ID_BAND_AT_NEXT) {
    keys.xy = uvec2(selected.x, front - DUAL_ID_BAND_AT_SELECTED);
    next_depths.x = next.x;
  } else {
    keys.xy = uvec2(floatBitsToUint(-next.x), front - DUAL_ID_BAND_AT_NEXT);
    next_depths.x = -select.y;
  }
  if (back < DUAL_ID_BAND_AT_NEXT) {
    keys.zw = uvec2(selected.z, DUAL_ID_MAX_ID - (back - DUAL_ID_BAND_AT_SELECTED));
    next_depths.y = next.y;
  } else {
    keys.zw = uvec2(floatBitsToUint(next.y), DUAL_ID_MAX_ID - (back - DUAL_ID_BAND_AT_NEXT));
    next_depths.y = -select.w;
  }
  // One fragment left: selected on both sides, composited once (front).
  if (u_count_back && keys.xy == keys.zw) discard;
  out_selected_keys = keys;
  out_next_depths = next_depths;
}
