// Adaptive transparency's per-pixel adaptive visibility function (AVF): up
// to slots.k nodes (depth z_i, transmittance T_i just behind z_i), sorted by
// depth, pixel-major (node i of pixel p at p * slots.k + i); the visibility at
// depth z is the T of the last node strictly in front of z, 1 before the
// first. How many nodes a pixel holds is its count word.
#include "shaders/bindings.h"
#include "shaders/pixel_slots.glsl"
#include "algorithms/adaptive_transparency/bindings.h"

layout(std430, binding = ADAPTIVE_TRANSPARENCY_NODES_BINDING) coherent buffer AvfNodes { vec2 avf_nodes[]; };
// Node removals (compressions) in the last frame; then the node count per pixel.
layout(std430, binding = ADAPTIVE_TRANSPARENCY_COUNTS_BINDING) coherent buffer AvfCounts {
  uint avf_removals;
  uint avf_counts[];
};
