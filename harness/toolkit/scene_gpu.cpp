#include "harness/toolkit/scene_gpu.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "shaders/bindings.h"

namespace oit {
namespace {

// The triangle ids as the shaders read them (OIT_UNIT_TRIANGLE_IDS); a
// scene with more triangles than the device's buffer textures hold fails
// here with the numbers, not with ids read as 0.
Texture triangle_ids_view(const Buffer& ids, size_t triangles) {
  GLint max_texels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
  if (uint64_t(triangles) > uint64_t(std::max(max_texels, 0)))
    throw std::runtime_error("scene: " + std::to_string(triangles) + " triangles, but this device's buffer textures " +
                             "hold " + std::to_string(max_texels) +
                             " texels (GL_MAX_TEXTURE_BUFFER_SIZE), the most triangles a scene may have here");
  return make_buffer_texture(ids, GL_R32UI);
}

uint64_t next_serial() {
  static std::atomic<uint64_t> next{1};
  return next++;
}

}  // namespace

SceneGpu::SceneGpu(const Scene& scene) : scene_(scene), serial_(next_serial()) {
  // GL rejects zero-sized buffer storage; an empty scene gets placeholders
  // (nothing is drawn from them).
  auto upload = [](size_t bytes, const void* data) {
    static const uint32_t placeholder[4] = {};
    return bytes > 0 ? make_buffer(GLsizeiptr(bytes), data, 0) : make_buffer(sizeof(placeholder), placeholder, 0);
  };
  vertices_ = upload(scene.vertices.size() * sizeof(Vertex), scene.vertices.data());
  indices_ = upload(scene.indices.size() * sizeof(uint32_t), scene.indices.data());
  triangle_ids_ = upload(scene.triangle_ids.size() * sizeof(uint32_t), scene.triangle_ids.data());
  triangle_ids_view_ = triangle_ids_view(triangle_ids_, scene.triangle_ids.size());
  bool finite = true;
  for (const auto& v : scene.vertices) {
    finite &= std::isfinite(v.position.x) && std::isfinite(v.position.y) && std::isfinite(v.position.z);
    box_.lo = box_.empty ? v.position : glm::min(box_.lo, v.position);
    box_.hi = box_.empty ? v.position : glm::max(box_.hi, v.position);
    box_.empty = false;
  }
  // A non-finite vertex bounds nothing: the infinite box makes the scene
  // rectangle the full image.
  if (!finite) box_ = {glm::vec3(-INFINITY), glm::vec3(INFINITY), false};
  bytes_ = scene.vertices.size() * sizeof(Vertex) + (scene.indices.size() + scene.triangle_ids.size()) * 4;

  vertex_array_ = make_vertex_array();
  const GLuint vao = vertex_array_.id();
  glVertexArrayVertexBuffer(vao, 0, vertices_.id(), 0, sizeof(Vertex));
  glVertexArrayElementBuffer(vao, indices_.id());
  auto float_attribute = [vao](GLuint location, GLint size, size_t offset) {
    glEnableVertexArrayAttrib(vao, location);
    glVertexArrayAttribFormat(vao, location, size, GL_FLOAT, GL_FALSE, GLuint(offset));
    glVertexArrayAttribBinding(vao, location, 0);
  };
  auto uint_attribute = [vao](GLuint location, size_t offset) {
    glEnableVertexArrayAttrib(vao, location);
    glVertexArrayAttribIFormat(vao, location, 1, GL_UNSIGNED_INT, GLuint(offset));
    glVertexArrayAttribBinding(vao, location, 0);
  };
  float_attribute(OIT_ATTRIB_POSITION, 3, offsetof(Vertex, position));
  float_attribute(OIT_ATTRIB_NORMAL, 3, offsetof(Vertex, normal));
  float_attribute(OIT_ATTRIB_COLOR, 4, offsetof(Vertex, color));
  uint_attribute(OIT_ATTRIB_OBJECT_ID, offsetof(Vertex, object_id));
  uint_attribute(OIT_ATTRIB_SURFACE_ID, offsetof(Vertex, surface_id));
  float_attribute(OIT_ATTRIB_UV, 2, offsetof(Vertex, uv));
  float_attribute(OIT_ATTRIB_MEAN_CURVATURE, 1, offsetof(Vertex, mean_curvature));
}

GLuint SceneGpu::flat_colors_view() const {
  if (!flat_colors_built_) build_flat_colors();
  flat_colors_built_ = true;
  return flat_colors_view_.id();
}

void SceneGpu::build_flat_colors() const {
  const size_t triangles = scene_.triangle_count();
  if (triangles == 0) return;
  const uint32_t largest = *std::max_element(scene_.triangle_ids.begin(), scene_.triangle_ids.end());
  GLint max_texels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
  // Sparse ids, or more than a buffer texture holds: no table.
  if (uint64_t(largest) >= 4 * uint64_t(triangles) + 16 || uint64_t(largest) >= uint64_t(max_texels)) return;
  std::vector<glm::vec4> colors(size_t(largest) + 1, glm::vec4(0.0f));
  std::vector<bool> seen(colors.size(), false);
  for (size_t t = 0; t < triangles; ++t) {
    const uint32_t id = scene_.triangle_ids[t];
    if (seen[id]) return;  // ids must be unique for the table to name one colour
    seen[id] = true;
    colors[id] = scene_.vertices[scene_.indices[3 * t + 2]].color;  // the provoking (last) vertex
  }
  flat_colors_ = make_buffer(GLsizeiptr(colors.size() * sizeof(glm::vec4)), colors.data(), 0);
  flat_colors_view_ = make_buffer_texture(flat_colors_, GL_RGBA32F);
  flat_colors_bytes_ = colors.size() * sizeof(glm::vec4);
}

void SceneGpu::bind() const {
  glBindVertexArray(vertex_array_.id());
  glBindTextureUnit(OIT_UNIT_TRIANGLE_IDS, triangle_ids_view_.id());
}

void SceneGpu::draw() const {
  bind();
  glDrawElements(GL_TRIANGLES, GLsizei(scene_.indices.size()), GL_UNSIGNED_INT, nullptr);
}

}  // namespace oit
