#pragma once
// One move-only RAII owner per GL object kind. Objects are created with the
// GL 4.5 direct-state-access entry points so no binding state leaks.
#include <initializer_list>
#include <utility>

#include "harness/gl/gl.h"

namespace oit {

template <typename Traits>
class GlHandle {
 public:
  GlHandle() = default;
  explicit GlHandle(GLuint id) : id_(id) {}
  GlHandle(const GlHandle&) = delete;
  GlHandle& operator=(const GlHandle&) = delete;
  GlHandle(GlHandle&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  GlHandle& operator=(GlHandle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  ~GlHandle() { reset(); }

  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_ != 0) Traits::destroy(id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

struct BufferTraits { static void destroy(GLuint id) { glDeleteBuffers(1, &id); } };
struct TextureTraits { static void destroy(GLuint id) { glDeleteTextures(1, &id); } };
struct FramebufferTraits { static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); } };
struct ProgramTraits { static void destroy(GLuint id) { glDeleteProgram(id); } };
struct ShaderTraits { static void destroy(GLuint id) { glDeleteShader(id); } };
struct VertexArrayTraits { static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); } };
struct QueryTraits { static void destroy(GLuint id) { glDeleteQueries(1, &id); } };

using Buffer = GlHandle<BufferTraits>;
using Texture = GlHandle<TextureTraits>;
using Framebuffer = GlHandle<FramebufferTraits>;
using Program = GlHandle<ProgramTraits>;
using Shader = GlHandle<ShaderTraits>;
using VertexArray = GlHandle<VertexArrayTraits>;
using Query = GlHandle<QueryTraits>;

inline Buffer make_buffer(GLsizeiptr bytes, const void* data = nullptr,
                          GLbitfield flags = GL_DYNAMIC_STORAGE_BIT) {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  // Zero-sized storage is invalid in GL; a 4-byte buffer keeps bindings legal.
  glNamedBufferStorage(id, bytes > 0 ? bytes : 4, bytes > 0 ? data : nullptr, flags);
  return Buffer(id);
}

// Sets every 32-bit word of `buffer` to `value` (list heads to a nil index,
// counters to zero).
inline void fill_buffer_u32(const Buffer& buffer, GLuint value) {
  glClearNamedBufferData(buffer.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &value);
}

// Binds each buffer to its GL_SHADER_STORAGE_BUFFER binding point (the
// technique's bindings.h names them): {{NODES_BINDING, &nodes_}, ...}.
inline void bind_storage_buffers(std::initializer_list<std::pair<GLuint, const Buffer*>> bindings) {
  for (const auto& [binding, buffer] : bindings) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer->id());
}

// A buffer texture reading `buffer` as `internal_format` texels: the whole
// buffer, or `bytes` from `offset` when bytes > 0 (offset aligned to
// GL_TEXTURE_BUFFER_OFFSET_ALIGNMENT).
inline Texture make_buffer_texture(const Buffer& buffer, GLenum internal_format, GLintptr offset = 0,
                                   GLsizeiptr bytes = 0) {
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_BUFFER, 1, &id);
  if (bytes > 0) {
    glTextureBufferRange(id, internal_format, buffer.id(), offset, bytes);
  } else {
    glTextureBuffer(id, internal_format, buffer.id());
  }
  return Texture(id);
}

inline Texture make_texture_2d(GLenum internal_format, int width, int height) {
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &id);
  glTextureStorage2D(id, 1, internal_format, width, height);
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return Texture(id);
}

inline Framebuffer make_framebuffer() {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  return Framebuffer(id);
}

inline VertexArray make_vertex_array() {
  GLuint id = 0;
  glCreateVertexArrays(1, &id);
  return VertexArray(id);
}

inline Query make_query(GLenum target) {
  GLuint id = 0;
  glCreateQueries(target, 1, &id);
  return Query(id);
}

}  // namespace oit
