#include "scenes/parametric.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <stdexcept>

namespace oit {
namespace {

// A point of a parametric surface: where it is, its unit normal and its
// analytic mean curvature.
struct SurfacePoint {
  glm::vec3 position;
  glm::vec3 normal;
  float mean_curvature;
};

// Appends the (slices + 1) x (stacks + 1) vertices of a surface, row by row
// in v: `point(u, v)` for u, v in [0, 1] (u = 1 has its own vertices, so
// the seam keeps distinct (u, v)); colour and ids are the surface's.
template <typename PointAt>
void append_grid_vertices(Scene& scene, int slices, int stacks, const glm::vec4& color, uint32_t object_id,
                          uint32_t surface_id, const PointAt& point) {
  for (int j = 0; j <= stacks; ++j) {
    const float v = float(j) / float(stacks);
    for (int i = 0; i <= slices; ++i) {
      const float u = float(i) / float(slices);
      const SurfacePoint p = point(u, v);
      Vertex vertex;
      vertex.position = p.position;
      vertex.normal = p.normal;
      vertex.color = color;
      vertex.object_id = object_id;
      vertex.surface_id = surface_id;
      vertex.uv = glm::vec2(u, v);
      vertex.mean_curvature = p.mean_curvature;
      scene.vertices.push_back(vertex);
    }
  }
}

}  // namespace

void append_uv_sphere(Scene& scene, const glm::vec3& center, float radius, int slices, int stacks,
                      const glm::vec4& color, uint32_t object_id, uint32_t surface_id) {
  if (slices < 3 || stacks < 2) throw std::invalid_argument("sphere needs at least 3 slices and 2 stacks");
  const auto base = uint32_t(scene.vertices.size());
  // Positions on the seam coincide, indices do not.
  append_grid_vertices(scene, slices, stacks, color, object_id, surface_id, [&](float u, float v) {
    const float theta = v * glm::pi<float>();
    const float phi = u * glm::two_pi<float>();
    const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
    return SurfacePoint{center + radius * n, n, 1.0f / radius};
  });
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

namespace {

// Indexes a (slices + 1) x (stacks + 1) grid of vertices starting at `base`
// as two triangles per cell.
void append_grid_triangles(Scene& scene, uint32_t base, int slices, int stacks) {
  const auto at = [&](int i, int j) { return base + uint32_t(j * (slices + 1) + i); };
  for (int j = 0; j < stacks; ++j) {
    for (int i = 0; i < slices; ++i) {
      scene.indices.insert(scene.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      scene.indices.insert(scene.indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      scene.triangle_ids.push_back(uint32_t(scene.triangle_ids.size()));
      scene.triangle_ids.push_back(uint32_t(scene.triangle_ids.size()));
    }
  }
}

const glm::vec3 kPalette[] = {{0.9f, 0.3f, 0.2f}, {0.2f, 0.7f, 0.3f}, {0.2f, 0.4f, 0.9f},
                              {0.9f, 0.8f, 0.2f}, {0.7f, 0.3f, 0.8f}, {0.2f, 0.8f, 0.8f}};

void check_tessellation(const SurfaceParams& p, const char* scene) {
  if (p.count < 1 || p.slices < 3 || p.stacks < 1)
    throw std::invalid_argument(std::string(scene) + ": needs count >= 1, slices >= 3, stacks >= 1");
}

}  // namespace

void append_torus(Scene& scene, const glm::mat4& to_world, float major_radius, float minor_radius, int slices,
                  int stacks, const glm::vec4& color, uint32_t object_id, uint32_t surface_id) {
  if (slices < 3 || stacks < 3) throw std::invalid_argument("torus needs at least 3 slices and 3 stacks");
  const auto base = uint32_t(scene.vertices.size());
  const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(to_world)));
  const float scale = std::cbrt(std::abs(glm::determinant(glm::mat3(to_world))));
  append_grid_vertices(scene, slices, stacks, color, object_id, surface_id, [&](float u, float v) {
    const float tube = v * glm::two_pi<float>();
    const float around = u * glm::two_pi<float>();
    const glm::vec3 radial(std::cos(around), 0.0f, std::sin(around));
    const glm::vec3 n = std::cos(tube) * radial + glm::vec3(0.0f, std::sin(tube), 0.0f);
    const glm::vec3 p = major_radius * radial + minor_radius * n;
    // H = (R + 2 r cos t) / (2 r (R + r cos t)) for the outward normal.
    const float c = std::cos(tube);
    return SurfacePoint{
        glm::vec3(to_world * glm::vec4(p, 1.0f)), glm::normalize(normal_matrix * n),
        (major_radius + 2.0f * minor_radius * c) / (2.0f * minor_radius * (major_radius + minor_radius * c)) / scale};
  });
  append_grid_triangles(scene, base, slices, stacks);
}

void append_open_cylinder(Scene& scene, const glm::vec3& center, float radius, float height, int slices,
                          int stacks, const glm::vec4& color, uint32_t object_id, uint32_t surface_id) {
  if (slices < 3 || stacks < 1) throw std::invalid_argument("cylinder needs at least 3 slices and 1 stack");
  const auto base = uint32_t(scene.vertices.size());
  append_grid_vertices(scene, slices, stacks, color, object_id, surface_id, [&](float u, float v) {
    const float around = u * glm::two_pi<float>();
    const glm::vec3 n(std::cos(around), 0.0f, std::sin(around));
    return SurfacePoint{center + radius * n + glm::vec3(0.0f, (v - 0.5f) * height, 0.0f), n, 0.5f / radius};
  });
  append_grid_triangles(scene, base, slices, stacks);
}

Scene make_torus(const SurfaceParams& params) {
  check_tessellation(params, "torus");
  Scene scene;
  scene.name = "torus";
  const glm::mat4 tilt = glm::rotate(glm::mat4(1.0f), glm::radians(60.0f), glm::vec3(1.0f, 0.0f, 0.0f));
  append_torus(scene, tilt, 1.0f, 0.35f, params.slices, params.stacks, glm::vec4(kPalette[2], params.alpha), 0, 0);
  scene.object_count = 1;
  scene.analytic_curvature = true;
  scene.camera = frame_bounding_sphere(scene.bounds());
  return scene;
}

Scene make_nested_spheres(const SurfaceParams& params) {
  check_tessellation(params, "nested_spheres");
  if (params.stacks < 2) throw std::invalid_argument("nested_spheres: needs stacks >= 2");
  Scene scene;
  scene.name = "nested_spheres";
  for (int s = 0; s < params.count; ++s) {
    const float radius = 1.0f - float(s) / float(params.count);
    append_uv_sphere(scene, glm::vec3(0.0f), radius, params.slices, params.stacks,
                     glm::vec4(kPalette[s % 6], params.alpha), uint32_t(s), uint32_t(s));
  }
  scene.object_count = uint32_t(params.count);
  scene.analytic_curvature = true;
  scene.camera = frame_bounding_sphere(scene.bounds());
  return scene;
}

Scene make_concentric_cylinders(const SurfaceParams& params) {
  check_tessellation(params, "cylinders");
  Scene scene;
  scene.name = "cylinders";
  for (int s = 0; s < params.count; ++s) {
    const float radius = 1.0f - 0.5f * float(s) / float(params.count);
    append_open_cylinder(scene, glm::vec3(0.0f), radius, 2.0f, params.slices, params.stacks,
                         glm::vec4(kPalette[s % 6], params.alpha), uint32_t(s), uint32_t(s));
  }
  scene.object_count = uint32_t(params.count);
  scene.analytic_curvature = true;
  const BoundingSphere bounds = scene.bounds();
  scene.camera = frame_bounding_sphere(bounds);
  // Look down at 35 degrees so the inner cylinders show through the outer ones.
  scene.camera.view = scene.camera.view * glm::rotate(glm::mat4(1.0f), glm::radians(35.0f), glm::vec3(1.0f, 0.0f, 0.0f));
  return scene;
}

Scene make_overlapping_spheres(const SurfaceParams& params) {
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
  scene.analytic_curvature = true;
  scene.camera = frame_bounding_sphere(scene.bounds());
  return scene;
}

}  // namespace oit
