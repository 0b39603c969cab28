#pragma once
// How the illustration buffer's compute passes cover a frame: once per
// stored fragment (per_fragment.glsl), per pixel, or per covered pixel
// (pixel_dispatch.glsl: the host's list of the pixels that hold a fragment
// with storage=linearized or arrays, whose counts it knows).
#include <cstdint>

#include "harness/gl/gl.h"

namespace oit::illustration_buffer {

struct Grid {
  int width = 0, height = 0;
  uint64_t fragments = 0;    // stored (sorted) fragments
  bool listed = false;       // the per-pixel passes run over the covered pixels
  GLuint covered_view = 0;   // R32UI: the covered pixels in raster order
  uint64_t covered = 0;

  // `program` once per stored fragment, in workgroups of 64.
  void per_fragment(GLuint program) const;
  // The bound `program` (built with ShaderVariant::listed = listed) once
  // per pixel, or once per covered pixel.
  void per_covered_pixel() const;
  // The bound program once per pixel, in 8x8 workgroups.
  void per_pixel() const;
};

// `invocations` in workgroups of 64, two-dimensional beyond 65535 groups
// (per_fragment.glsl, pixel_dispatch.glsl flatten the index back).
void dispatch_in_groups_of_64(uint64_t invocations);

}  // namespace oit::illustration_buffer
