#version 450 core
// One dual peeling pass with tie_break=triangle_id (see by_id_shared.glsl).
// The front and back fragments the previous pass selected are blended under
// the front and over the back accumulation (fixed-function blending; every
// other fragment outputs zero, which leaves them unchanged; a fragment that
// is both, the last one left, goes to the front only). The fragments strictly
// between the two keys feed four GL_MIN reductions: the front candidate, the
// nearest depth beyond the front's next depth, the back candidate, and
// (negated) the farthest depth before the back's next depth.
#include "shaders/shading.glsl"
#include "algorithms/dual_depth_peeling/by_id_shared.glsl"

layout(binding = DUAL_ID_KEYS_UNIT) uniform usampler2D u_selected_keys;  // front depth, id, back depth, id
layout(binding = DUAL_ID_NEXT_UNIT) uniform sampler2D u_next_depths;     // -front next, back next

layout(location = 0) out vec4 out_front;   // premultiplied rgb, alpha: under
layout(location = 1) out vec4 out_back;    // straight rgba: over
layout(location = 2) out vec4 out_select;  // GL_MIN

void main() {
  const ivec2 pixel = ivec2(gl_FragCoord.xy);
  const uvec4 selected = texelFetch(u_selected_keys, pixel, 0);
  const float front_depth = uintBitsToFloat(selected.x), back_depth = uintBitsToFloat(selected.z);
  const float depth = oit_view_depth();
  if (depth < front_depth || depth > back_depth) discard;  // composited in an earlier pass
  const vec2 next = texelFetch(u_next_depths, pixel, 0).xy;
  const float front_next = -next.x, back_next = next.y;
  const bool at_front = depth == front_depth, at_back = depth == back_depth;
  const bool at_front_next = depth == front_next, at_back_next = depth == back_next;
  // Only fragments at one of the four depths need their id (a storage-buffer read).
  const uint id = at_front || at_back || at_front_next || at_back_next ? oit_triangle_id() : 0u;
  if ((at_front && id < selected.y) || (at_back && id > selected.w)) discard;  // tied, composited before
  out_front = vec4(0.0);
  out_back = vec4(0.0);
  out_select = vec4(DUAL_ID_NO_CANDIDATE);
  if (at_front && id == selected.y) {
    const vec4 color = oit_shade();
    out_front = vec4(color.rgb * color.a, color.a);
    return;
  }
  if (at_back && id == selected.w) {
    out_back = oit_shade();
    return;
  }
  if (at_front) {
    out_select.x = dual_id_front_candidate(DUAL_ID_BAND_AT_SELECTED, id);
  } else if (at_front_next) {
    out_select.x = dual_id_front_candidate(DUAL_ID_BAND_AT_NEXT, id);
  } else if (depth > front_next) {
    out_select.y = depth;
  }
  if (at_back) {
    out_select.z = dual_id_back_candidate(DUAL_ID_BAND_AT_SELECTED, id);
  } else if (at_back_next) {
    out_select.z = dual_id_back_candidate(DUAL_ID_BAND_AT_NEXT, id);
  } else if (depth < back_next) {
    out_select.w = -depth;
  }
}
