// Included by broken.frag; line 3 below is a deliberate type error that the
// shader-loader test expects to be reported as this file's line 3.
float broken_value() { return vec2(1.0); }
