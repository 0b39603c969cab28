#version 450 core
// Final write: the front-to-back accumulation (rgb premultiplied, alpha =
// transmittance) over the background.
#include "shaders/compose.glsl"
#include "algorithms/depth_peeling/peel_shared.glsl"

layout(binding = DEPTH_PEELING_ACCUMULATION_UNIT) uniform sampler2D u_accumulation;

layout(location = 0) out vec4 out_color;

void main() {
  const vec4 accumulated = texelFetch(u_accumulation, ivec2(gl_FragCoord.xy), 0);
  out_color = oit_finish(accumulated.rgb, accumulated.a);
}
