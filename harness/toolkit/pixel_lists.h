#pragma once
// The buffers of the per-pixel linked lists (A-buffer) that linked_list and
// reference fill: each pixel's heads and list length, the frame's counters
// (the node count first) and the node pool, which the technique allocates
// when its FragmentPool says so. The layouts (nodes, heads per pixel,
// counters) are each technique's own; the fill loop over them is the same:
// clear, bind, draw, read the counters back, again while the pool grew.
#include <functional>
#include <span>

#include "harness/toolkit/fragment_pool.h"
#include "harness/toolkit/technique.h"
#include "harness/gl/handles.h"

namespace oit {

// The technique's binding points of the four buffers (its bindings.h).
struct PixelListBindings {
  GLuint heads, nodes, counters, lengths;
};

class PixelLists {
 public:
  PixelLists(const PixelListBindings& bindings, GLsizeiptr counter_bytes)
      : counters(make_buffer(counter_bytes)), bindings_(bindings) {}

  void bind() const {
    bind_storage_buffers({{bindings_.heads, &heads},
                          {bindings_.nodes, &nodes},
                          {bindings_.counters, &counters},
                          {bindings_.lengths, &lengths}});
  }

  // FragmentPool::fill_until_fits over the lists: stage "clear" sets every
  // head nil (0xffffffff, the shaders' NIL) and every length and counter
  // zero; stage "fill" binds the lists, runs `draw` (the geometry pass) and
  // reads the first counts.size() counters into `counts`, whose first is the
  // nodes the fill produced. Returns the fills run.
  uint64_t fill_until_fits(const Frame& frame, FragmentPool& pool, const std::function<void()>& draw,
                           std::span<GLuint> counts) const {
    return pool.fill_until_fits(
        frame,
        [&] {
          fill_buffer_u32(heads, 0xffffffffu);
          fill_buffer_u32(lengths, 0);
          fill_buffer_u32(counters, 0);
        },
        [&] {
          bind();
          draw();
          glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
          glGetNamedBufferSubData(counters.id(), 0, GLsizeiptr(counts.size_bytes()), counts.data());
          return uint64_t(counts[0]);
        });
  }

  Buffer heads, lengths, counters, nodes;

 private:
  PixelListBindings bindings_;
};

}  // namespace oit
