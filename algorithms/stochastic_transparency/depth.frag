#version 450 core
// Stochastic depth pass (Enderton et al. 2010, section 3): each fragment
// covers a random subset of the pixel's SAMPLES samples, each sample with
// probability alpha, through gl_SampleMask; the depth test (LESS) keeps, per
// sample, the nearest fragment that covered it (its depth at that sample).
#include "shaders/shading.glsl"
#include "algorithms/stochastic_transparency/bindings.h"

layout(location = STOCHASTIC_TRANSPARENCY_SEED_LOCATION) uniform uint u_seed;

// A 32-bit integer hash with full avalanche (the PCG output permutation
// applied to an LCG step): random numbers from (pixel, triangle, seed)
// without any state, so a fragment's mask does not depend on the order in
// which fragments arrive.
uint stochastic_hash(uint x) {
  const uint state = x * 747796405u + 2891336453u;
  const uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

float unit_random(inout uint state) {
  state = stochastic_hash(state);
  return float(state >> 8) * (1.0 / 16777216.0);
}

void main() {
  const float alpha = oit_shade().a;
  uint state = stochastic_hash(u_seed ^ stochastic_hash(oit_triangle_id() ^
                                  stochastic_hash(uint(oit_image_pixel().x) | (uint(oit_image_pixel().y) << 16))));
  // floor(alpha S + u), u uniform in [0, 1): on average exactly alpha S samples.
  const uint covered = min(uint(alpha * float(SAMPLES) + unit_random(state)), uint(SAMPLES));
  // Which samples: the first `covered` entries of a random permutation
  // (Fisher-Yates), so every subset of that size is equally likely.
  uint order[SAMPLES];
  for (uint i = 0u; i < uint(SAMPLES); ++i) order[i] = i;
  uint mask = 0u;
  for (uint i = 0u; i < covered; ++i) {
    const uint j = i + min(uint(unit_random(state) * float(uint(SAMPLES) - i)), uint(SAMPLES) - i - 1u);
    const uint picked = order[j];
    order[j] = order[i];
    mask |= 1u << picked;
  }
  gl_SampleMask[0] = int(mask);
}
