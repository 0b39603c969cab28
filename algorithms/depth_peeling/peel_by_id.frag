#version 450 core
// One depth-peeling pass with tie_break=triangle_id (see by_id_shared.glsl).
// The fragment the previous pass selected is blended under the accumulation
// (fixed-function "under" blending; every other fragment outputs zero, which
// leaves the accumulation unchanged). The fragments not composited yet feed
// two GL_MIN reductions: the candidate key of the next fragment, and the
// nearest depth beyond `next` (the next `next` if the candidate at `next`
// wins). No depth test: the order is decided by exact float compares.
#include "shaders/shading.glsl"
#include "algorithms/depth_peeling/by_id_shared.glsl"

layout(binding = DP_ID_STATE_UNIT) uniform usampler2D u_state;  // selected depth, id, next depth

layout(location = 0) out vec4 out_accumulation;  // premultiplied rgb, alpha: under
layout(location = 1) out vec2 out_select;        // GL_MIN: (candidate key, depth beyond next)

void main() {
  const uvec3 state = texelFetch(u_state, ivec2(gl_FragCoord.xy), 0).xyz;
  const float selected_depth = uintBitsToFloat(state.x);
  const uint selected_id = state.y;
  const float next_depth = uintBitsToFloat(state.z);
  const float depth = oit_view_depth();
  if (depth < selected_depth) discard;  // composited in an earlier pass
  const bool at_selected = depth == selected_depth;
  const bool at_next = depth == next_depth;
  // Only fragments at one of the two depths need their id (a storage-buffer read).
  const uint id = at_selected || at_next ? oit_triangle_id() : 0u;
  if (at_selected && id < selected_id) discard;  // tied, composited in an earlier pass
  out_accumulation = vec4(0.0);
  out_select = vec2(DP_ID_NO_CANDIDATE);
  if (at_selected && id == selected_id) {
    const vec4 color = oit_shade();
    out_accumulation = vec4(color.rgb * color.a, color.a);
  } else if (at_selected) {
    out_select.x = dp_id_candidate(DP_ID_BAND_AT_SELECTED, id);
  } else if (at_next) {
    out_select.x = dp_id_candidate(DP_ID_BAND_AT_NEXT, id);
  } else if (depth > next_depth) {
    out_select.y = depth;
  }
  // (No fragment lies between the selected and the next depth: `next` is the
  // nearest beyond. One that did would never be composited, and would show
  // up in fragments_dropped, which is counted as all minus composited.)
}
