#version 450 core
// Final write: front layers (premultiplied, transmittance in alpha) over the
// back layers (premultiplied "over" result, transmittance in alpha) over the
// background.
#include "shaders/compose.glsl"
#include "algorithms/dual_depth_peeling/dual_shared.glsl"

layout(binding = DUAL_PEELING_FRONT_UNIT) uniform sampler2D u_front;
layout(binding = DUAL_PEELING_BACK_UNIT) uniform sampler2D u_back;

layout(location = 0) out vec4 out_color;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 front = texelFetch(u_front, pixel, 0);
  vec4 back = texelFetch(u_back, pixel, 0);
  out_color = oit_finish(front.rgb + front.a * back.rgb, front.a * back.a);
}
