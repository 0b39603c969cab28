#include "algorithms/illustration_buffer/triangle_table.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace oit::illustration_buffer {
namespace {

struct PositionBits {
  uint32_t x, y, z;
  bool operator==(const PositionBits&) const = default;
};

struct PositionHash {
  size_t operator()(const PositionBits& p) const {
    uint64_t h = 1469598103934665603ull;
    for (uint32_t word : {p.x, p.y, p.z}) h = (h ^ word) * 1099511628211ull;
    return size_t(h);
  }
};

PositionBits bits_of(const glm::vec3& position) {
  // +0 and -0 are the same point.
  const glm::vec3 p = position + glm::vec3(0.0f);
  PositionBits bits;
  std::memcpy(&bits.x, &p.x, 4);
  std::memcpy(&bits.y, &p.y, 4);
  std::memcpy(&bits.z, &p.z, 4);
  return bits;
}

// canonical[i]: the index that stands for vertex i (the first vertex at the
// same position when welding, else i itself).
std::vector<uint32_t> canonical_indices(const Scene& scene, bool weld) {
  std::vector<uint32_t> canonical(scene.vertices.size());
  if (!weld) {
    for (size_t i = 0; i < canonical.size(); ++i) canonical[i] = uint32_t(i);
    return canonical;
  }
  std::unordered_map<PositionBits, uint32_t, PositionHash> first_at;
  first_at.reserve(scene.vertices.size());
  for (size_t i = 0; i < canonical.size(); ++i)
    canonical[i] = first_at.try_emplace(bits_of(scene.vertices[i].position), uint32_t(i)).first->second;
  return canonical;
}

}  // namespace

TriangleTable build_triangle_table(const Scene& scene, bool weld_vertices) {
  const size_t triangles = scene.triangle_count();
  if (scene.triangle_ids.size() != triangles)
    throw std::invalid_argument("illustration_buffer: scene '" + scene.name +
                                "' has a triangle id count different from its triangle count");
  const std::vector<uint32_t> canonical = canonical_indices(scene, weld_vertices);
  uint32_t largest_id = 0;
  for (uint32_t id : scene.triangle_ids) largest_id = std::max(largest_id, id);
  TriangleTable table;
  // Rows of ids no triangle has (none in the library scenes) match nothing.
  table.vertices_by_stable_id.assign(triangles > 0 ? size_t(largest_id) + 1 : 0, glm::uvec4(0xffffffffu));
  std::vector<uint32_t> uses(scene.vertices.size(), 0);
  for (size_t t = 0; t < triangles; ++t) {
    glm::uvec4 row(0u);
    for (int k = 0; k < 3; ++k) {
      row[k] = canonical.at(scene.indices[3 * t + size_t(k)]);
      ++uses[row[k]];
    }
    table.vertices_by_stable_id[scene.triangle_ids[t]] = row;
  }
  for (size_t t = 0; t < triangles; ++t) {
    bool shared = false;
    for (int k = 0; k < 3; ++k) shared = shared || uses[canonical[scene.indices[3 * t + size_t(k)]]] > 1;
    table.isolated_triangles += !shared;
  }
  return table;
}

}  // namespace oit::illustration_buffer
