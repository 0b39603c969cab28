#pragma once
// CPU-side scene: one merged, indexed triangle mesh plus a camera. Every
// technique draws it with ONE draw call, so gl_PrimitiveID is the triangle's
// position in `indices`; `triangle_ids` gives each submitted triangle a
// stable id used as the depth tie-break, independent of submission order.
#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace oit {

struct Vertex {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  // Straight (not premultiplied) RGBA; constant per triangle (read flat from
  // the provoking = last vertex of each triangle).
  glm::vec4 color{1.0f};
  uint32_t object_id = 0;   // distinct object / shape id (BKB buckets)
  uint32_t surface_id = 0;  // parametric surface id (neighbour accuracy)
  glm::vec2 uv{0.0f};       // surface parameters
  // Analytic mean curvature (1/length, outward normal positive: a sphere of
  // radius r has 1/r) where the scene knows it; see Scene::analytic_curvature.
  float mean_curvature = 0.0f;
};

// A camera independent of the image aspect ratio: projection(aspect) builds
// the matrix for the image being rendered.
struct Camera {
  glm::mat4 view{1.0f};
  bool orthographic = false;
  float yfov_radians = 0.8f;   // perspective
  float ymag = 1.0f;           // orthographic half height
  float xmag = 0.0f;           // orthographic half width; 0 = ymag * aspect
  float znear = 0.1f;
  float zfar = 100.0f;
  glm::mat4 projection(float aspect) const;
};

struct BoundingSphere {
  glm::vec3 center{0.0f};
  float radius = 0.0f;
};

struct Scene {
  std::string name;    // library id or file path
  std::string params;  // canonical scene parameters ("" for files)
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;       // 3 per triangle
  std::vector<uint32_t> triangle_ids;  // 1 per triangle, stable across reorderings
  uint32_t object_count = 0;
  bool lit = true;                     // false: colour is output unshaded (unlit materials)
  bool analytic_curvature = false;     // every vertex's mean_curvature is exact
  Camera camera;

  size_t triangle_count() const { return indices.size() / 3; }
  BoundingSphere bounds() const;
  // Stable hash of geometry, colours and camera: the key of cached references.
  std::string content_hash() const;
  // Throws naming the scene when indices are out of range or positions are
  // not finite.
  void validate() const;
};

// A camera looking at the bounding sphere from +z so that it fills the view.
Camera frame_bounding_sphere(const BoundingSphere& sphere);
// The same from the side `direction` points to (from the centre towards the
// eye; need not be normalised, must not be zero).
Camera frame_bounding_sphere(const BoundingSphere& sphere, const glm::vec3& direction);

// The camera of the synthetic quad scenes: orthographic, the [-1, 1] square
// of view space seen down -z from `znear` to `zfar`.
Camera orthographic_square_camera(float znear, float zfar);

// Appends a square facing the camera (normal +z) at view depth
// z = -distance, `center` +- `half` in x and y, uv 0..1 across it: two
// triangles with the ids 2 * quad and 2 * quad + 1. The synthetic quad
// scenes (quads, random_quads, stress_layers) are built of these.
void append_facing_quad(Scene& scene, glm::vec2 center, float half, float distance, const glm::vec4& color,
                        uint32_t object_id, uint32_t surface_id, uint32_t quad);

}  // namespace oit

namespace oit {

// Reorders the submitted triangles without changing the scene: "original",
// "reversed", "shuffled:SEED" (every triangle), or "objects_shuffled:SEED"
// (whole objects in shuffled order). Triangle ids move with their triangles,
// so exact techniques must produce the same image. Throws on other text.
void reorder_triangles(Scene& scene, const std::string& order);

}  // namespace oit
