#version 450 core
// Pass 2: every fragment again, weighted by the visibility function at its
// depth (the T of the last node strictly in front of it), summed
// additively: (sum vis a rgb, sum vis a).
#include "shaders/shading.glsl"
#include "algorithms/adaptive_transparency/avf_storage.glsl"

layout(location = 0) out vec4 out_accumulation;

void main() {
  const vec4 color = oit_shade();
  const float depth = oit_view_depth();
  const uint pixel = slots_pixel();
  const uint first = pixel * uint(slots.k + 1);
  float visibility = 1.0;
  for (uint i = 0u; i < avf_counts[pixel]; ++i) {
    const vec2 node = avf_nodes[first + i];
    if (node.x >= depth) break;
    visibility = node.y;
  }
  out_accumulation = visibility * color.a * vec4(color.rgb, 1.0);
}
