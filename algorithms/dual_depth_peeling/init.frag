#version 450 core
#include "shaders/subgroup_atomics.glsl"
// First geometry pass: the nearest and farthest depth of every pixel
// (GL_MAX blending of (-depth, depth)).
#include "shaders/shading.glsl"
#include "algorithms/dual_depth_peeling/dual_shared.glsl"

layout(location = 0) out vec2 out_range;

void main() {
  float depth = oit_view_depth();
  DUAL_PEELING_COUNT_LEFT_UNPEELED();  // max_passes = 1: nothing gets composited
  out_range = vec2(-depth, depth);
}
