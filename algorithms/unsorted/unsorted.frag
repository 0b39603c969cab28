#version 450 core
// Plain "over" blending in submission order (fixed-function blend state).
#include "shaders/shading.glsl"

layout(location = 0) out vec4 out_color;

void main() { out_color = oit_shade(); }
