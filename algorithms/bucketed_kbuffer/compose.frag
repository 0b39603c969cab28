#version 450 core
// Blending (murray2016 section 3, step 3): the pixel's stored fragments in
// depth order, composited back to front. Equal quantised depths (possible
// only within one shape, or across shapes closer than one depth step) are
// ordered by the packed colour so the image never depends on the order in
// which fragments arrived.
#include "shaders/compose.glsl"
#include "algorithms/bucketed_kbuffer/bkb_common.glsl"

layout(location = 0) out vec4 out_color;

uint depths[K];
uint colors[K];

void main() {
  uint base = bkb_pixel_base();
  int count = 0;
  for (int i = 0; i < K; ++i) {
    uint slot = base + uint(i);
    uint key = bkb_z[slot];
    if (key == BKB_EMPTY) break;
    if (bkb_normals[slot] == 0u) continue;  // no data stored (counted as a store miss)
    depths[count] = bkb_depth(key);
    colors[count] = bkb_colors[slot];
    ++count;
  }
  for (int i = 1; i < count; ++i) {
    uint depth = depths[i], color = colors[i];
    int j = i - 1;
    while (j >= 0 && (depths[j] > depth || (depths[j] == depth && colors[j] > color))) {
      depths[j + 1] = depths[j];
      colors[j + 1] = colors[j];
      --j;
    }
    depths[j + 1] = depth;
    colors[j + 1] = color;
  }
  vec3 accumulated = vec3(0.0);  // premultiplied, over everything behind
  float transmittance = 1.0;
  for (int i = count - 1; i >= 0; --i) {
    vec4 c = unpackUnorm4x8(colors[i]);
    accumulated = c.a * c.rgb + (1.0 - c.a) * accumulated;
    transmittance *= 1.0 - c.a;
  }
  out_color = oit_finish(accumulated, transmittance);
}
