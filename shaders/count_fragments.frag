#version 450 core
// Counts the fragments of every pixel (depth complexity). Shared by the
// harness's complexity pass and by techniques that size buffers from it.
#include "shaders/bindings.h"

layout(early_fragment_tests) in;
layout(binding = 0, r32ui) uniform coherent uimage2D u_fragment_counts;

void main() {
  imageAtomicAdd(u_fragment_counts, ivec2(gl_FragCoord.xy), 1u);
}
