#version 450 core
// The empty frame of Harness::frame_overhead_ms: drawn with rasterizer
// discard, so no fragment reaches it.
void main() {}
