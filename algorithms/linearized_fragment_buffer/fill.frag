#version 450 core
// Fill pass of the linearized fragment buffer: every fragment takes the next
// free slot of its pixel's range, offset[pixel] + (an atomic increment of the
// pixel's own cursor), and writes its sort key and colour there. No global
// counter: the atomics of different pixels never touch the same word.
#include "shaders/shading.glsl"
#include "algorithms/linearized_fragment_buffer/storage.glsl"

// pixels + 1 exclusive prefix sums of the counts: pixel p owns [offset[p], offset[p+1]).
layout(std430, binding = OIT_FIRST_TECHNIQUE_BINDING + 0) readonly buffer LfbOffsets { uint lfb_offsets[]; };
// Fragments written so far per pixel (cleared before the fill): afterwards the list lengths.
layout(std430, binding = OIT_FIRST_TECHNIQUE_BINDING + 1) coherent buffer LfbCursors { uint lfb_cursors[]; };
layout(std430, binding = OIT_FIRST_TECHNIQUE_BINDING + 2) writeonly buffer LfbKeys { uvec2 lfb_keys[]; };
layout(std430, binding = OIT_FIRST_TECHNIQUE_BINDING + 3) writeonly buffer LfbColors { vec4 lfb_colors[]; };
// Fragments that found their pixel's range full: the counting pass counted
// fewer than the fill produced. Never expected (the same geometry under the
// same state rasterizes to the same fragments); the host fails loudly if not.
layout(std430, binding = OIT_FIRST_TECHNIQUE_BINDING + 6) coherent buffer LfbOverflow { uint lfb_overflow; };
layout(location = OIT_FIRST_TECHNIQUE_UNIFORM + 1) uniform int u_width;

void main() {
  const uint pixel = uint(gl_FragCoord.y) * uint(u_width) + uint(gl_FragCoord.x);
  const uint slot = lfb_offsets[pixel] + atomicAdd(lfb_cursors[pixel], 1u);
  if (slot >= lfb_offsets[pixel + 1u]) {
    atomicAdd(lfb_overflow, 1u);
    return;
  }
  lfb_keys[slot] = uvec2(lfb_depth_order(floatBitsToUint(oit_view_depth())), oit_triangle_id());
  lfb_colors[slot] = oit_shade();
}
