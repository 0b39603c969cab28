#pragma once
// Parametric test surfaces as indexed triangle meshes. Every vertex keeps its
// surface id and (u, v) in [0, 1]^2 so fragments can be traced back to the
// surface they lie on.
#include <cstdint>

#include "scenes/scene.h"

namespace oit {

// Appends a closed UV sphere (mean curvature 1/radius) (shared vertices, poles included) to `scene`.
void append_uv_sphere(Scene& scene, const glm::vec3& center, float radius, int slices, int stacks,
                      const glm::vec4& color, uint32_t object_id, uint32_t surface_id);

// Appends a closed torus around the local y axis, transformed by `to_world`
// (rigid or uniformly scaled). u runs around the axis, v around the tube
// (v = 0 on the outer equator).
void append_torus(Scene& scene, const glm::mat4& to_world, float major_radius, float minor_radius, int slices,
                  int stacks, const glm::vec4& color, uint32_t object_id, uint32_t surface_id);

// Appends an open cylinder (no caps) around the y axis from y = -h/2 to h/2.
void append_open_cylinder(Scene& scene, const glm::vec3& center, float radius, float height, int slices,
                          int stacks, const glm::vec4& color, uint32_t object_id, uint32_t surface_id);

struct SurfaceParams {
  int count = 3;      // spheres / cylinders; ignored by the torus
  int slices = 64;
  int stacks = 32;
  float alpha = 0.4f;
};

// `count` closed spheres whose centres lie on a circle, overlapping their
// neighbours: depth complexity varies from 0 to 2 * count across the image.
// Lit, perspective camera framing the bounding sphere.
Scene make_overlapping_spheres(const SurfaceParams& params);

// One torus (R = 1, r = 0.35) tilted 60 degrees towards the viewer: up to 4
// layers, positive and negative curvature. Lit, perspective.
Scene make_torus(const SurfaceParams& params);
// `count` concentric spheres of radii 1, ..., 1/count: 2 * count layers at
// the centre. Lit, perspective.
Scene make_nested_spheres(const SurfaceParams& params);
// `count` concentric open cylinders (carnecky2013 Fig. 2) seen from above at
// an angle. Lit, perspective.
Scene make_concentric_cylinders(const SurfaceParams& params);

}  // namespace oit
