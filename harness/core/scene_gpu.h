#pragma once
#include "harness/core/scene_rect.h"
#include "harness/gl/handles.h"
#include "scenes/scene.h"

namespace oit {

// A scene uploaded once: vertex/index buffers, the triangle-id SSBO and a
// vertex array in the shared attribute layout (shaders/bindings.h).
class SceneGpu {
 public:
  explicit SceneGpu(const Scene& scene);
  const Scene& scene() const { return scene_; }
  // Binds the vertex array and the triangle-id buffer; techniques call draw().
  void bind() const;
  // One draw call over every triangle, so gl_PrimitiveID = triangle index.
  void draw() const;
  size_t bytes() const { return bytes_; }
  // Of every vertex, computed once here (the harness's scene rectangle).
  const BoundingBox& bounding_box() const { return box_; }

 private:
  const Scene& scene_;
  Buffer vertices_, indices_, triangle_ids_;
  VertexArray vertex_array_;
  size_t bytes_ = 0;
  BoundingBox box_;
};

}  // namespace oit
