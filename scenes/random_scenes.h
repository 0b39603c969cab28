#pragma once
// Randomised synthetic scenes whose statistics are set by parameters:
// overlapping screen-aligned quads (depth complexity and submission order
// under control) and many small separate objects (object-id heavy).
#include <cstdint>
#include <string>

#include "scenes/scene.h"

namespace oit {

struct RandomQuadsParams {
  int count = 64;          // quads
  float size = 0.5f;       // side as a fraction of the view's width
  uint32_t seed = 1;
  float alpha = 0.3f;
  // "random", "front_to_back" or "back_to_front": the submission order.
  std::string order = "random";
};

// Axis-aligned quads of side `size` at random positions in the orthographic
// [-1, 1]^2 view and at distinct random depths; unlit. The expected depth
// complexity of a pixel is about count * size^2.
Scene make_random_quads(const RandomQuadsParams& params);

struct ParticlesParams {
  int per_axis = 6;   // per_axis^3 small spheres on a jittered grid
  int slices = 8;
  int stacks = 6;
  float alpha = 0.5f;
  uint32_t seed = 1;
};

// Many small separate closed spheres, one object id each; lit, perspective.
Scene make_particles(const ParticlesParams& params);

}  // namespace oit
