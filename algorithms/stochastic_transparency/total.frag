#version 450 core
// Total transmittance for the alpha correction (Enderton et al., section
// 3.4): prod (1 - alpha) over every fragment, (ZERO, ONE_MINUS_SRC_COLOR)
// blending into a single-sampled target.
#include "shaders/shading.glsl"

layout(location = 0) out vec4 out_alpha;

void main() { out_alpha = vec4(oit_shade().a); }
