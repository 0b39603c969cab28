#pragma once
// The auxiliary table of pastyrik2016 Figure 5(d): for every triangle, by its
// STABLE id (the id oit_triangle_id() returns), the indices of its 3 vertices.
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "scenes/scene.h"

namespace oit::illustration_buffer {

struct TriangleTable {
  std::vector<glm::uvec4> vertices_by_stable_id;  // xyz: vertex indices, w: 0 (std430 uvec4 stride)
  // Triangles sharing no vertex with any other triangle: the triangle-index
  // search can never link their fragments (all of them become silhouettes).
  uint64_t isolated_triangles = 0;
};

// `scene.indices` is in SUBMISSION order (3 per submitted triangle) and
// `scene.triangle_ids[t]` is the stable id of submitted triangle t, so the
// row of stable id triangle_ids[t] holds indices[3t .. 3t+2]. With
// `weld_vertices`, vertices at bitwise-equal positions count as one index
// (closes the duplicated-vertex seams of UV-parametrised meshes).
TriangleTable build_triangle_table(const Scene& scene, bool weld_vertices);

}  // namespace oit::illustration_buffer
