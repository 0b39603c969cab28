#version 450 core
// Counting pass of techniques that size per-pixel storage from the view
// (harness/toolkit/list_length_pass.h): every fragment adds 1 to its pixel by additive
// blending into an R32F target (exact up to 2^24 fragments per pixel). On
// llvmpipe this is ~8x faster than an atomic counter per fragment (see
// list_length_pass.cpp).
layout(location = 0) out float out_count;

void main() { out_count = 1.0; }
