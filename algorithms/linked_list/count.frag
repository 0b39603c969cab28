#version 450 core
#include "shaders/subgroup_atomics.glsl"
// Counting pass of pool_sizing=count: one geometry pass that only counts the
// fragments the fill will produce (one atomic add each; no shading, no list
// writes), so the host can size the node pool exactly before the fill.
// (Aggregated per subgroup where the driver allows: subgroup_atomics.glsl.)
#include "algorithms/linked_list/nodes.glsl"

void main() { OIT_ATOMIC_COUNT(ll_node_count); }
