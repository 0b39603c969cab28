#pragma once
// Parametric test surfaces as indexed triangle meshes. Every vertex keeps its
// surface id and (u, v) in [0, 1]^2 so fragments can be traced back to the
// surface they lie on.
#include <cstdint>

#include "scene.h"

namespace oit {

// Appends a closed UV sphere (shared vertices, poles included) to `scene`.
void append_uv_sphere(Scene& scene, const glm::vec3& center, float radius, int slices, int stacks,
                      const glm::vec4& color, uint32_t object_id, uint32_t surface_id);

struct OverlappingSpheresParams {
  int count = 3;
  int slices = 32;
  int stacks = 16;
  float alpha = 0.4f;
};

// `count` closed spheres whose centres lie on a circle, overlapping their
// neighbours: depth complexity varies from 0 to 2 * count across the image.
// Lit, perspective camera framing the bounding sphere.
Scene make_overlapping_spheres(const OverlappingSpheresParams& params);

}  // namespace oit
