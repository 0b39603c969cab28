#version 450 core
// Counting pass of pool_sizing=count: the fragments of the fill's geometry,
// counted by a GL_SAMPLES_PASSED query around this pass (linked_list.cpp).
// Nothing to do per fragment: no shading, no list writes, no atomics.
void main() {}
