#version 450 core
// Early exit: survives only where the range the last pass found is non-empty,
// so an occlusion query around this full-screen pass tells whether another
// peeling pass has anything to do (without a geometry pass to find out).
#include "algorithms/dual_depth_peeling/dual_shared.glsl"

layout(binding = DUAL_PEELING_RANGE_UNIT) uniform sampler2D u_range;

void main() {
  vec2 range = texelFetch(u_range, ivec2(gl_FragCoord.xy), 0).xy;
  if (-range.x > range.y) discard;  // nearest > farthest: nothing left
}
