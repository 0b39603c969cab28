// Multi-layer alpha blending's per-pixel state: up to slots.k layers sorted
// front to back, each a premultiplied colour with its transmittance and the
// depth of its nearest fragment; pixel-major (layer i of pixel p at
// p * slots.k + i). How many layers a pixel holds is its count word.
#include "shaders/bindings.h"
#include "shaders/pixel_slots.glsl"
#include "algorithms/multi_layer_alpha_blending/bindings.h"

// (premultiplied rgb, transmittance) of each layer.
layout(std430, binding = MULTI_LAYER_ALPHA_BLENDING_COLORS_BINDING) coherent buffer MlabColors { vec4 mlab_colors[]; };
layout(std430, binding = MULTI_LAYER_ALPHA_BLENDING_DEPTHS_BINDING) coherent buffer MlabDepths { float mlab_depths[]; };
// Layers in use per pixel; then, after the pixels, the fragments merged
// into a farther layer (kept only approximately) in the last frame.
layout(std430, binding = MULTI_LAYER_ALPHA_BLENDING_COUNTS_BINDING) coherent buffer MlabCounts {
  uint mlab_merges;
  uint mlab_counts[];
};
