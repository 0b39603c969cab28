#pragma once
#include <cstdint>

#include "harness/toolkit/scene_rect.h"
#include "harness/gl/handles.h"
#include "harness/gl/shader_program.h"
#include "scenes/scene.h"

namespace oit {

// A scene uploaded once: vertex/index buffers, the triangle-id SSBO and a
// vertex array in the shared attribute layout (shaders/bindings.h).
class SceneGpu {
 public:
  explicit SceneGpu(const Scene& scene);
  const Scene& scene() const { return scene_; }
  // Unique to this upload within the process, never reused: the key of any
  // per-scene data a technique keeps between frames. (A later scene can be
  // built at an earlier one's address, as when the viewer loads another.)
  uint64_t serial() const { return serial_; }
  // What the programs that draw this scene may be built for (SceneShadingScope).
  SceneShading shading() const { return scene_.lit ? SceneShading::lit : SceneShading::unlit; }
  // Binds the vertex array and the triangle-id buffer; techniques call draw().
  void bind() const;
  // One draw call over every triangle, so gl_PrimitiveID = triangle index.
  void draw() const;
  size_t bytes() const { return bytes_; }
  // Every fragment's material colour is its triangle's flat colour
  // (shading.glsl: v_color, read from the provoking vertex); unlit scenes
  // shade with exactly it, lit ones multiply its rgb by oit_light_factor().
  // So a technique that stores a fragment's stable triangle id (and on lit
  // scenes the factor) can rebuild its exact colour later instead of storing
  // 16 bytes of it. This buffer texture (RGBA32F, indexed by stable triangle
  // id) holds those colours; 0 for scenes whose stable ids are not unique or
  // are far larger than the triangle count (no table is worth building
  // then). Built on the first
  // call, so scenes pay nothing unless a technique asks; the technique counts
  // flat_colors_bytes() in its memory.
  GLuint flat_colors_view() const;
  size_t flat_colors_bytes() const { return flat_colors_bytes_; }
  // Of every vertex, computed once here (the harness's scene rectangle).
  const BoundingBox& bounding_box() const { return box_; }

 private:
  const Scene& scene_;
  uint64_t serial_;
  void build_flat_colors() const;

  Buffer vertices_, indices_, triangle_ids_;
  Texture triangle_ids_view_;
  mutable Buffer flat_colors_;
  mutable Texture flat_colors_view_;
  mutable bool flat_colors_built_ = false;
  mutable size_t flat_colors_bytes_ = 0;
  VertexArray vertex_array_;
  size_t bytes_ = 0;
  BoundingBox box_;
};

}  // namespace oit
