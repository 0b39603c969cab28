// Storage of the reference: every fragment in a per-pixel linked list.
#include "shaders/pixel_storage.glsl"
#include "algorithms/reference/bindings.h"

#define REFERENCE_NIL 0xffffffffu

// Read and written as whole vectors: on Mesa 22.3 llvmpipe, reading single
// scalar members of a struct array in a loop returned wrong values.
struct ReferenceNode {
  vec4 color;  // straight RGBA from oit_shade()
  uvec4 link;  // x: view depth (float bits), y: stable triangle id, z: next node, w: unused
};

layout(std430, binding = REFERENCE_HEADS_BINDING) coherent buffer ReferenceHeads { uint heads[]; };
layout(std430, binding = REFERENCE_NODES_BINDING) buffer ReferenceNodes { ReferenceNode nodes[]; };
// node_count: fragments the last fill produced; may exceed the capacity,
// which is how the host detects overflow. max_length: the longest list, from
// which the host sizes the resolve's local array.
layout(std430, binding = REFERENCE_COUNTER_BINDING) coherent buffer ReferenceCounter {
  uint node_count;
  uint max_length;
};
layout(std430, binding = REFERENCE_LENGTHS_BINDING) coherent buffer ReferenceLengths { uint lengths[]; };

layout(std140, binding = REFERENCE_PARAMS_BLOCK) uniform ReferenceBlock { ReferenceParams reference; };
