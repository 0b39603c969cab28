#version 450 core
#include "shaders/subgroup_atomics.glsl"
// One dual peeling pass (Bavoil & Myers 2008). The previous pass found each
// pixel's remaining depth range [nearest, farthest]. Fragments outside it were
// composited before: discarded. The fragment at `nearest` is blended under
// the front accumulation, the one at `farthest` over the back accumulation
// (both by the fixed-function blend, see dual_depth_peeling.cpp; a zero
// output leaves them unchanged). Fragments strictly inside feed GL_MAX the
// next range. When one fragment is both nearest and farthest (the middle
// layer of an odd count), it is composited to the front only.
#include "shaders/shading.glsl"
#include "algorithms/dual_depth_peeling/dual_shared.glsl"

layout(binding = DUAL_PEELING_RANGE_UNIT) uniform sampler2D u_previous_range;

layout(location = 0) out vec2 out_range;  // GL_MAX
layout(location = 1) out vec4 out_front;  // premultiplied rgb, alpha: under
layout(location = 2) out vec4 out_back;   // straight rgba: over

void main() {
  vec2 range = texelFetch(u_previous_range, ivec2(gl_FragCoord.xy), 0).xy;
  float nearest = -range.x;
  float farthest = range.y;
  float depth = oit_view_depth();
  if (depth < nearest || depth > farthest) discard;
  out_front = vec4(0.0);
  out_back = vec4(0.0);
  if (depth > nearest && depth < farthest) {
    out_range = vec2(-depth, depth);
    DUAL_PEELING_COUNT_LEFT_UNPEELED();
    return;
  }
  out_range = DUAL_PEELING_EMPTY_RANGE;
  vec4 color = oit_shade();
  if (depth == nearest) {
    out_front = vec4(color.rgb * color.a, color.a);
  } else {
    out_back = color;
  }
}
