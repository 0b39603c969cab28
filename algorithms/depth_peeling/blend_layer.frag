#version 450 core
// Blends the layer the last pass peeled under everything peeled before it.
// The fixed-function blend (see depth_peeling.cpp) does
//   accumulated += transmittance * premultiplied, transmittance *= 1 - alpha.
// Pixels where the pass found nothing are discarded, so the occlusion query
// around this pass counts exactly the fragments peeled by it.
#include "algorithms/depth_peeling/peel_shared.glsl"

layout(binding = DEPTH_PEELING_LAYER_COLOR_UNIT) uniform sampler2D u_layer_color;
layout(binding = DEPTH_PEELING_LAYER_KEYS_UNIT) uniform usampler2D u_layer_keys;

layout(location = 0) out vec4 out_color;

void main() {
  const ivec2 pixel = ivec2(gl_FragCoord.xy);
  if (texelFetch(u_layer_keys, pixel, 0).x == DEPTH_PEELING_EMPTY_DEPTH_BITS) discard;
  out_color = texelFetch(u_layer_color, pixel, 0);
}
