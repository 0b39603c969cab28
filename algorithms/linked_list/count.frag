#version 450 core
// Counting pass of pool_sizing=count: one geometry pass that only counts the
// fragments the fill will produce (one atomic add each; no shading, no list
// writes), so the host can size the node pool exactly before the fill.
#include "algorithms/linked_list/nodes.glsl"

void main() { atomicAdd(ll_node_count, 1u); }
