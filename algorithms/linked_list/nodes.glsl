// Storage of the per-pixel linked lists (Yang et al. 2010): LL_HEADS head
// pointers and a list length per pixel, one pool of nodes, and global counters.
#include "shaders/pixel_storage.glsl"
#include "algorithms/linked_list/bindings.h"

#define LL_NIL 0xffffffffu
// Each pixel's fragments are spread over LL_HEADS interleaved lists: the
// fragment at position p (its index in the pixel, from the length atomic)
// goes to list p % LL_HEADS. The resolve walks the lists side by side, so
// LL_HEADS node loads are independent and their memory latencies overlap
// (one list is a chain of dependent loads, ~2 MB apart on 256x256 quads).
// LL_HEADS is in bindings.h.

#if defined(LL_COMPACT)
// storage=compact: 12 bytes a node, three words: view depth (float bits),
// straight RGBA packed as RGBA8 (packUnorm4x8), next node. No triangle id:
// coplanar fragments are ordered by node index (see README).
#define LL_NODE_WORDS 3u
#else
// Read and written as whole vectors: on Mesa 22.3 llvmpipe, reading single
// scalar members of a struct array in a loop returned wrong values.
struct LinkedListNode {
  vec4 color;  // straight RGBA from oit_shade(), unpacked float
  uvec4 link;  // x: view depth (float bits), y: stable triangle id, z: next node, w: unused (std430 padding)
};
#endif

// Pixel p's list c starts at ll_heads[p * LL_HEADS + c].
layout(std430, binding = LINKED_LIST_HEADS_BINDING) coherent buffer LinkedListHeads { uint ll_heads[]; };
#if defined(LL_COMPACT)
layout(std430, binding = LINKED_LIST_NODES_BINDING) buffer LinkedListNodes { uint ll_words[]; };
#else
layout(std430, binding = LINKED_LIST_NODES_BINDING) buffer LinkedListNodes { LinkedListNode ll_nodes[]; };
#endif
// node_count: fragments the fill produced (may exceed the pool: that is how
// the host sees an overflow). max_length: the longest list, which sizes the
// resolve. dropped: fragments beyond max_per_pixel in their pixel, which the
// resolve will not composite.
layout(std430, binding = LINKED_LIST_COUNTERS_BINDING) coherent buffer LinkedListCounters {
  uint ll_node_count;
  uint ll_max_length;
  uint ll_dropped;
};
layout(std430, binding = LINKED_LIST_LENGTHS_BINDING) coherent buffer LinkedListLengths { uint ll_lengths[]; };

layout(std140, binding = LINKED_LIST_PARAMS_BLOCK) uniform LinkedListBlock { LinkedListParams ll; };

uint ll_pixel() { return oit_pixel_index(ll.width); }
