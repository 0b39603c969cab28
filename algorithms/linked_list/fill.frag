#version 450 core
#include "shaders/subgroup_atomics.glsl"
// Fill pass: every fragment is appended to its pixel's list. The pixel's
// length is counted even when the pool is full, so the host learns both how
// many nodes it needs and how long the longest list is.
#include "shaders/shading.glsl"
#include "algorithms/linked_list/nodes.glsl"

void main() {
  const uint pixel = ll_pixel();
  const uint position = atomicAdd(ll_lengths[pixel], 1u);
  OIT_ATOMIC_RAISE(ll_max_length, position + 1u);
  // Counted here, composited nowhere: the resolve keeps the nearest max_per_pixel.
  if (position >= ll.max_per_pixel) OIT_ATOMIC_COUNT(ll_dropped);
  uint index;
  OIT_ATOMIC_APPEND(ll_node_count, index);
  if (index >= ll.capacity) return;  // pool overflow: the host grows the pool and re-renders
  const uint next = atomicExchange(ll_heads[pixel * uint(LL_HEADS) + position % uint(LL_HEADS)], index);
#if defined(LL_COMPACT)
  ll_words[LL_NODE_WORDS * index + 0u] = floatBitsToUint(oit_view_depth());
  ll_words[LL_NODE_WORDS * index + 1u] = packUnorm4x8(oit_shade());
  ll_words[LL_NODE_WORDS * index + 2u] = next;
#else
  ll_nodes[index] = LinkedListNode(oit_shade(), uvec4(floatBitsToUint(oit_view_depth()), oit_triangle_id(), next, 0u));
#endif
}
