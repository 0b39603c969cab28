#version 450 core
#include "algorithms/multi_layer_alpha_blending/bindings.h"
// The one geometry pass of multi-layer alpha blending (Salvi & Vaidyanathan
// 2014): inside the pixel's ordered critical section, insert the fragment
// as a layer (premultiplied colour, transmittance 1 - a, depth) at its
// sorted place; when that makes slots.k + 1 layers, merge the two farthest
// with the over operator: C = C_near + T_near C_far, T = T_near T_far, at
// the nearer depth. Fragments arriving front to back are thus composed
// exactly for any k; in other orders the merged tail is approximate.
#define OIT_ORDERED_LOCK_BINDING MULTI_LAYER_ALPHA_BLENDING_LOCKS_BINDING
#include "shaders/ordered_access.glsl"
#include "shaders/shading.glsl"
#include "algorithms/multi_layer_alpha_blending/mlab_storage.glsl"

void insert_layer(uint pixel, vec4 layer, float depth) {
  const uint first = pixel * uint(slots.k);
  const uint count = mlab_counts[pixel];
  // Shift farther layers back by one (the last one into a virtual slot
  // slots.k when the pixel is full), then place the fragment. Equal depths
  // keep arrival order: the new fragment goes behind them.
  uint slot = count;
  vec4 overflow_color = vec4(0.0);
  float overflow_depth = 0.0;
  bool overflow = false;
  while (slot > 0u && mlab_depths[first + slot - 1u] > depth) {
    if (slot == uint(slots.k)) {
      overflow = true;
      overflow_color = mlab_colors[first + slot - 1u];
      overflow_depth = mlab_depths[first + slot - 1u];
    } else {
      mlab_colors[first + slot] = mlab_colors[first + slot - 1u];
      mlab_depths[first + slot] = mlab_depths[first + slot - 1u];
    }
    --slot;
  }
  if (slot == uint(slots.k)) {
    // Farther than every layer of a full pixel: it is the virtual layer.
    overflow = true;
    overflow_color = layer;
    overflow_depth = depth;
  } else {
    mlab_colors[first + slot] = layer;
    mlab_depths[first + slot] = depth;
  }
  if (!overflow) {
    mlab_counts[pixel] = count + 1u;
    return;
  }
  // Merge the virtual layer into the last real one (it lies behind it).
  const vec4 near = mlab_colors[first + uint(slots.k) - 1u];
  mlab_colors[first + uint(slots.k) - 1u] = vec4(near.rgb + near.a * overflow_color.rgb, near.a * overflow_color.a);
  atomicAdd(mlab_merges, 1u);
}

void main() {
  const vec4 color = oit_shade();
  const vec4 layer = vec4(color.rgb * color.a, 1.0 - color.a);
  const float depth = oit_view_depth();
  const uint pixel = slots_pixel();
  // No early return before OIT_ORDERED (interlock forbids it): a fully
  // transparent fragment just does nothing inside.
  OIT_ORDERED(pixel, if (color.a > 0.0) insert_layer(pixel, layer, depth))
}
