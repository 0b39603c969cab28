#version 450 core
// First pass of tie_break=triangle_id: each pixel's nearest view depth, into
// the GL_MIN reduction that the resolve turns into the first `next` depth.
#include "shaders/shading.glsl"
#include "algorithms/depth_peeling/by_id_shared.glsl"

layout(location = 0) out vec2 out_select;  // GL_MIN: (no candidate, nearest depth)

void main() { out_select = vec2(DP_ID_NO_CANDIDATE, oit_view_depth()); }
