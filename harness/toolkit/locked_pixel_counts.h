#pragma once
// The bookkeeping of a technique that edits up to k entries per pixel in
// the pixel's critical section (shaders/ordered_access.glsl):
// adaptive_transparency's visibility nodes, multi_layer_alpha_blending's
// layers. One buffer holds a count of the frame's events (entries removed
// or merged) and then every pixel's entry count; the locks are PixelLocks'.
#include <cstdint>
#include <string>
#include <utility>

#include "harness/toolkit/pixel_locks.h"
#include "harness/toolkit/technique.h"
#include "harness/gl/handles.h"

namespace oit {

class LockedPixelCounts {
 public:
  // Per pixel, the entry count (the events' word and the locks aside).
  static constexpr uint64_t kBytesPerPixel = 4;

  void resize(int width, int height) {
    pixels_ = uint64_t(width) * uint64_t(height);
    counts_ = make_buffer(GLsizeiptr(4 + pixels_ * kBytesPerPixel));
    locks_.resize(width, height);
  }
  // Every count to zero and every lock free (start of a frame).
  void clear() const {
    fill_buffer_u32(counts_, 0);
    locks_.clear();
  }
  void bind(GLuint counts_binding, GLuint locks_binding) const {
    bind_storage_buffers({{counts_binding, &counts_}});
    locks_.bind(locks_binding);
  }
  // Adds the counts' and the locks' bytes to `c.bytes_allocated`, counts the
  // fragments whose critical section never ran as dropped, and reports the
  // frame's events as `events_name` with the locks' counters. Reads back:
  // not for timed code.
  void report(TechniqueCounters& c, const std::string& events_name) const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint events = 0;
    glGetNamedBufferSubData(counts_.id(), 0, 4, &events);
    c.bytes_allocated += pixels_ * kBytesPerPixel + 4 + locks_.bytes();
    c.fragments_dropped = locks_.failures();
    c.extra.push_back({events_name, double(events)});
    for (auto& counter : locks_.counters()) c.extra.push_back(std::move(counter));
  }

 private:
  uint64_t pixels_ = 0;
  Buffer counts_;
  PixelLocks locks_;
};

}  // namespace oit
