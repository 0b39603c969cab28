#version 450 core
// Compose: the summed colours cover 1 - T_last, the exact total coverage
// (the last node is never removed); the sum is renormalised to it, as
// moment_oit and stochastic_transparency do, so that a visibility function
// that lets too much through after compression cannot push the pixel above
// its true opacity (a choice of ours, README).
#include "shaders/compose.glsl"
#include "algorithms/adaptive_transparency/avf_storage.glsl"
#include "algorithms/adaptive_transparency/bindings.h"

layout(binding = ADAPTIVE_TRANSPARENCY_ACCUMULATION_UNIT) uniform sampler2D u_accumulation;

layout(location = 0) out vec4 out_color;

void main() {
  const uint pixel = slots_pixel();
  const uint count = avf_counts[pixel];
  const float total_transmittance = count > 0u ? avf_nodes[pixel * uint(slots.k + 1) + count - 1u].y : 1.0;
  const vec4 accumulation = texelFetch(u_accumulation, ivec2(gl_FragCoord.xy), 0);
  const vec3 average = accumulation.a > 0.0 ? accumulation.rgb / accumulation.a : vec3(0.0);
  out_color = oit_finish(average * (1.0 - total_transmittance), total_transmittance);
}
