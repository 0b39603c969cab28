#pragma once
// The C++ side of shaders/ordered_access.glsl: its lock buffer (a failure
// counter, then one lock word per pixel), cleared every frame, and what a
// technique reports about it.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "harness/toolkit/technique.h"
#include "harness/gl/handles.h"

namespace oit {

class PixelLocks {
 public:
  // (Re)allocates the lock words of width x height pixels.
  void resize(int width, int height);
  // Frees every lock and zeroes the failure counter (start of a frame).
  void clear() const;
  // Binds the buffer at OIT_ORDERED_LOCK_BINDING's value.
  void bind(GLuint binding) const;
  uint64_t bytes() const { return bytes_; }
  // Invocations that gave up on their lock in the last frame (spin-lock
  // fallback only; always 0 under interlock). Reads back: not for timed code.
  uint32_t failures() const;
  // `extra` counters: lock_failures, interlock (1 when the shaders were
  // built with a fragment shader interlock extension, 0 on the fallback).
  std::vector<Figure> counters() const;

 private:
  Buffer buffer_;
  uint64_t bytes_ = 0;
};

}  // namespace oit
