#pragma once
// The one way to give a technique's shaders its parameters: one std140
// uniform block, whose struct the technique declares once in its
// algorithms/<id>/bindings.h for C++ and GLSL alike (GLSL's scalar names in
// C++: shaders/std140.h), together with the block's binding point. The
// shaders declare `layout(std140, binding = <ID>_PARAMS_BLOCK) uniform
// <Name> { <Struct> <instance>; };`; the C++ owns a UniformBlock<Struct>,
// sets `values` where they change and uploads them before the first pass
// of each frame that reads them (and again where a value changes between
// the passes of a frame, such as a pool that grew). Uploading binds the
// block too: binding points are global GL state that the techniques of a
// bench block, rendered in turns, share.
#include <type_traits>

#include "harness/gl/gl.h"
#include "harness/gl/handles.h"

namespace oit {

template <typename Params>
class UniformBlock {
  static_assert(std::is_trivially_copyable_v<Params>, "a parameter block is copied to the GPU as bytes");
  // std140 rounds a struct's size up to 16 bytes and aligns a vec2 to 8, a
  // vec4 to 16: the structs hold 4-byte scalars, padded to whole 16 bytes,
  // so that C++ lays them out as GLSL does.
  static_assert(sizeof(Params) % 16 == 0 && alignof(Params) == 4,
                "a parameter block holds 4-byte scalars padded to a multiple of 16 bytes");

 public:
  // `binding`: the block's binding point (algorithms/<id>/bindings.h).
  explicit UniformBlock(GLuint binding) : binding_(binding), buffer_(make_buffer(sizeof(Params))) {}

  Params values{};

  // Writes `values` to the block's buffer and binds it at its binding point.
  void upload() const {
    glNamedBufferSubData(buffer_.id(), 0, sizeof(Params), &values);
    glBindBufferBase(GL_UNIFORM_BUFFER, binding_, buffer_.id());
  }

 private:
  GLuint binding_;
  Buffer buffer_;
};

}  // namespace oit
