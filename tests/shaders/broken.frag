#version 450 core
#include "tests/shaders/broken_include.glsl"
layout(location = 0) out vec4 out_color;
void main() { out_color = vec4(broken_value()); }
