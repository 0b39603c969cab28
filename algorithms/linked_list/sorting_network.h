#pragma once
// The fixed sorting networks of the linked list's `network` resolve: the
// comparator list is generated here and turned into GLSL macro text, so the
// shader is one straight line of compare-exchanges on constant indices.
#include <cstdint>
#include <string>
#include <vector>

#include "harness/gl/shader_program.h"

namespace oit::linked_list {

// After the comparator, element `first` precedes element `second` (first < second).
struct Comparator {
  uint32_t first;
  uint32_t second;
};

// Batcher's odd-even merge sort for `size` >= 1 elements: the network of the
// next power of two without the comparators that touch a position >= size.
// Those positions would hold +infinity padding, which no comparator ever
// moves down, so the pruned comparators could never swap anything.
std::vector<Comparator> odd_even_merge_sort(uint32_t size);

// Applies `network` to `values` on the CPU (used by the tests).
void apply_network(const std::vector<Comparator>& network, std::vector<uint32_t>& values);

// The #defines of algorithms/linked_list/resolve.frag for `sort`
// ("insertion", "selection" or "network") and a local array of `capacity`
// elements. For the network they also carry the unrolled load, network and
// blend as macro sequences.
ShaderDefines resolve_defines(const std::string& sort, uint32_t capacity);

}  // namespace oit::linked_list
