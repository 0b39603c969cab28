#version 450 core
// Compose: the pixel's layers front to back.
#include "shaders/compose.glsl"
#include "algorithms/multi_layer_alpha_blending/mlab_storage.glsl"

layout(location = 0) out vec4 out_color;

void main() {
  const uint pixel = slots_pixel();
  const uint first = pixel * uint(slots.k);
  vec3 accumulated = vec3(0.0);
  float transmittance = 1.0;
  for (uint i = 0u; i < mlab_counts[pixel]; ++i) {
    const vec4 layer = mlab_colors[first + i];
    accumulated += transmittance * layer.rgb;
    transmittance *= layer.a;
  }
  out_color = oit_finish(accumulated, transmittance);
}
