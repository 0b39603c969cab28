#include "parametric.h"

#include <glm/gtc/constants.hpp>

#include <cmath>
#include <stdexcept>

namespace oit {

void append_uv_sphere(Scene& scene, const glm::vec3& center, float radius, int slices, int stacks,
                      const glm::vec4& color, uint32_t object_id, uint32_t surface_id) {
  if (slices < 3 || stacks < 2) throw std::invalid_argument("sphere needs at least 3 slices and 2 stacks");
  const auto base = uint32_t(scene.vertices.size());
  // (slices + 1) columns so that u = 1 has its own vertices (the seam keeps
  // distinct (u, v)); positions on the seam coincide, indices do not.
  for (int j = 0; j <= stacks; ++j) {
    const float v = float(j) / float(stacks);
    const float theta = v * glm::pi<float>();
    for (int i = 0; i <= slices; ++i) {
      const float u = float(i) / float(slices);
      const float phi = u * glm::two_pi<float>();
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      Vertex vertex;
      vertex.position = center + radius * n;
      vertex.normal = n;
      vertex.color = color;
      vertex.object_id = object_id;
      vertex.surface_id = surface_id;
      vertex.uv = glm::vec2(u, v);
      scene.vertices.push_back(vertex);
    }
  }
  const auto at = [&](int i, int j) { return base + uint32_t(j * (slices + 1) + i); };
  for (int j = 0; j < stacks; ++j) {
    for (int i = 0; i < slices; ++i) {
      // Degenerate triangles at the poles are skipped.
      if (j != 0) {
        scene.indices.insert(scene.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        scene.triangle_ids.push_back(uint32_t(scene.triangle_ids.size()));
      }
      if (j != stacks - 1) {
        scene.indices.insert(scene.indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        scene.triangle_ids.push_back(uint32_t(scene.triangle_ids.size()));
      }
    }
  }
}

Scene make_overlapping_spheres(const OverlappingSpheresParams& params) {
  if (params.count < 1) throw std::invalid_argument("spheres: count must be >= 1");
  Scene scene;
  scene.name = "spheres";
  scene.lit = true;
  const glm::vec3 palette[] = {{0.9f, 0.3f, 0.2f}, {0.2f, 0.7f, 0.3f}, {0.2f, 0.4f, 0.9f},
                               {0.9f, 0.8f, 0.2f}, {0.7f, 0.3f, 0.8f}, {0.2f, 0.8f, 0.8f}};
  const float ring = params.count == 1 ? 0.0f : 0.6f;
  for (int s = 0; s < params.count; ++s) {
    const float angle = glm::two_pi<float>() * float(s) / float(params.count);
    // A slight tilt in z so the spheres overlap in depth as well as on screen.
    const glm::vec3 center(ring * std::cos(angle), ring * std::sin(angle), 0.3f * std::sin(2.0f * angle));
    append_uv_sphere(scene, center, 0.8f, params.slices, params.stacks,
                     glm::vec4(palette[s % 6], params.alpha), uint32_t(s), uint32_t(s));
  }
  scene.object_count = uint32_t(params.count);
  scene.camera = frame_bounding_sphere(scene.bounds());
  return scene;
}

}  // namespace oit
