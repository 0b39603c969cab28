#version 450 core
// Writes the injected VALUE and the value of the shared header's constant,
// so a test can read back that #define injection and #include both worked.
#include "shaders/bindings.h"
layout(location = 0) out vec4 out_color;
void main() { out_color = vec4(VALUE, float(OIT_FIRST_TECHNIQUE_UNIFORM), 0.0, 1.0); }
