#include "scenes/scene.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace oit {

glm::mat4 Camera::projection(float aspect) const {
  if (orthographic) {
    const float half_width = xmag > 0.0f ? xmag : ymag * aspect;
    return glm::ortho(-half_width, half_width, -ymag, ymag, znear, zfar);
  }
  return glm::perspective(yfov_radians, aspect, znear, zfar);
}

BoundingSphere Scene::bounds() const {
  if (vertices.empty()) return {};
  glm::vec3 lo(vertices[0].position), hi(vertices[0].position);
  for (const auto& v : vertices) {
    lo = glm::min(lo, v.position);
    hi = glm::max(hi, v.position);
  }
  BoundingSphere sphere{(lo + hi) * 0.5f, 0.0f};
  for (const auto& v : vertices) sphere.radius = std::max(sphere.radius, glm::length(v.position - sphere.center));
  return sphere;
}

std::string Scene::content_hash() const {
  // FNV-1a over the raw bytes: stable, dependency-free, good enough to key a cache.
  uint64_t hash = 1469598103934665603ull;
  auto mix = [&hash](const void* data, size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i) hash = (hash ^ p[i]) * 1099511628211ull;
  };
  mix(vertices.data(), vertices.size() * sizeof(Vertex));
  mix(indices.data(), indices.size() * sizeof(uint32_t));
  mix(triangle_ids.data(), triangle_ids.size() * sizeof(uint32_t));
  // Field by field: Camera has padding bytes whose contents are undefined.
  mix(&camera.view, sizeof(camera.view));
  mix(&camera.orthographic, sizeof(camera.orthographic));
  for (float value : {camera.yfov_radians, camera.ymag, camera.xmag, camera.znear, camera.zfar})
    mix(&value, sizeof(value));
  mix(&lit, sizeof(lit));
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

void Scene::validate() const {
  if (indices.size() % 3 != 0) throw std::invalid_argument(name + ": index count is not a multiple of 3");
  if (triangle_ids.size() != triangle_count())
    throw std::invalid_argument(name + ": triangle id count does not match the triangle count");
  for (size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] >= vertices.size()) {
      throw std::invalid_argument(name + ": index " + std::to_string(i) + " = " + std::to_string(indices[i]) +
                                  " is past the vertex count " + std::to_string(vertices.size()));
    }
  }
  for (size_t i = 0; i < vertices.size(); ++i) {
    const glm::vec3& p = vertices[i].position;
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      throw std::invalid_argument(name + ": vertex " + std::to_string(i) + " has a non-finite position");
    }
  }
}

Camera orthographic_square_camera(float znear, float zfar) {
  Camera camera;
  camera.orthographic = true;
  camera.xmag = camera.ymag = 1.0f;
  camera.znear = znear;
  camera.zfar = zfar;
  return camera;
}

void append_facing_quad(Scene& scene, glm::vec2 center, float half, float distance, const glm::vec4& color,
                        uint32_t object_id, uint32_t surface_id, uint32_t quad) {
  const auto base = uint32_t(scene.vertices.size());
  for (glm::vec2 corner : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
    Vertex v;
    v.position = glm::vec3(center + corner * half, -distance);
    v.color = color;
    v.object_id = object_id;
    v.surface_id = surface_id;
    v.uv = corner * 0.5f + 0.5f;
    scene.vertices.push_back(v);
  }
  for (uint32_t index : {0u, 1u, 2u, 0u, 2u, 3u}) scene.indices.push_back(base + index);
  scene.triangle_ids.push_back(2 * quad);
  scene.triangle_ids.push_back(2 * quad + 1);
}

Camera frame_bounding_sphere(const BoundingSphere& sphere) {
  return frame_bounding_sphere(sphere, glm::vec3(0.0f, 0.0f, 1.0f));
}

Camera frame_bounding_sphere(const BoundingSphere& sphere, const glm::vec3& direction) {
  Camera camera;
  const float radius = sphere.radius > 0.0f ? sphere.radius : 1.0f;
  camera.yfov_radians = glm::radians(45.0f);
  // Distance at which the sphere touches the top and bottom of the view.
  const float distance = radius / std::sin(camera.yfov_radians * 0.5f);
  const glm::vec3 toward_eye = glm::normalize(direction);
  const glm::vec3 eye = sphere.center + toward_eye * distance;
  // World +y is up unless the view looks (almost) along it.
  const glm::vec3 up = std::abs(toward_eye.y) > 0.99f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  camera.view = glm::lookAt(eye, sphere.center, up);
  camera.znear = std::max(distance - radius * 1.01f, distance * 1e-3f);
  camera.zfar = distance + radius * 1.01f;
  return camera;
}

}  // namespace oit

#include <numeric>
#include <random>

namespace oit {

void reorder_triangles(Scene& scene, const std::string& order) {
  std::vector<size_t> permutation(scene.triangle_count());
  std::iota(permutation.begin(), permutation.end(), size_t(0));
  if (order == "original") return;
  auto seed_of = [&](size_t prefix) {
    try {
      size_t used = 0;
      const unsigned long seed = std::stoul(order.substr(prefix), &used);
      if (used != order.size() - prefix) throw std::invalid_argument("");
      return uint32_t(seed);
    } catch (const std::exception&) {
      throw std::invalid_argument("submission order '" + order + "': seed is not a number");
    }
  };
  if (order == "reversed") {
    std::reverse(permutation.begin(), permutation.end());
  } else if (order.rfind("shuffled:", 0) == 0) {
    std::mt19937 rng(seed_of(9));
    for (size_t i = permutation.size(); i > 1; --i) std::swap(permutation[i - 1], permutation[rng() % i]);
  } else if (order.rfind("objects_shuffled:", 0) == 0) {
    // Whole objects in a shuffled order, each object's triangles in their
    // original order: what a renderer that sorts draw calls does.
    std::mt19937 rng(seed_of(17));
    std::vector<uint32_t> rank(size_t(scene.object_count) + 1);
    std::iota(rank.begin(), rank.end(), 0u);
    for (size_t i = rank.size(); i > 1; --i) std::swap(rank[i - 1], rank[rng() % i]);
    auto object_of = [&](size_t t) {
      return std::min<size_t>(scene.vertices[scene.indices[3 * t + 2]].object_id, rank.size() - 1);
    };
    std::stable_sort(permutation.begin(), permutation.end(),
                     [&](size_t a, size_t b) { return rank[object_of(a)] < rank[object_of(b)]; });
  } else {
    throw std::invalid_argument("submission order '" + order +
                                "' is not original, reversed, shuffled:SEED or objects_shuffled:SEED");
  }
  std::vector<uint32_t> indices(scene.indices.size());
  std::vector<uint32_t> ids(scene.triangle_ids.size());
  for (size_t t = 0; t < permutation.size(); ++t) {
    for (size_t k = 0; k < 3; ++k) indices[3 * t + k] = scene.indices[3 * permutation[t] + k];
    ids[t] = scene.triangle_ids[permutation[t]];
  }
  scene.indices = std::move(indices);
  scene.triangle_ids = std::move(ids);
}

}  // namespace oit
