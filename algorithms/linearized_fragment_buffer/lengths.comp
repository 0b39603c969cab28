#version 450 core
// After the fill: every pixel's cursor, which started at the pixel's offset
// and was incremented once per fragment, becomes the pixel's list length
// (what the resolve and linked_list's classify.comp read), and every pixel
// whose cursor did not end exactly at the next pixel's offset is counted.
// Such a mismatch means the counting pass and the fill rasterized different
// fragments (never expected: the same geometry under the same state); the
// fill then wrote into the next pixel's range, so the host fails the frame.
// One check per pixel here instead of a bounds check per fragment in the
// fill, where it cost ~10% of the fill.
#include "algorithms/linearized_fragment_buffer/bindings.h"

layout(local_size_x = 256) in;

layout(std430, binding = LFB_OFFSETS_BINDING) readonly buffer LfbOffsets { uint lfb_offsets[]; };
layout(std430, binding = LFB_CURSORS_BINDING) buffer LfbCursors { uint lfb_cursors[]; };
layout(std430, binding = LFB_MISMATCHED_BINDING) coherent buffer LfbOverflow { uint lfb_mismatched_pixels; };
layout(location = LFB_PIXELS_LOCATION) uniform uint u_pixels;

void main() {
  const uint pixel = gl_GlobalInvocationID.x;
  if (pixel >= u_pixels) return;
  const uint end = lfb_cursors[pixel];
  if (end != lfb_offsets[pixel + 1u]) atomicAdd(lfb_mismatched_pixels, 1u);
  lfb_cursors[pixel] = end - lfb_offsets[pixel];
}
