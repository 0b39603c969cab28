#pragma once
// The fixed sorting networks of the linked list's `network` resolve: the
// comparator list is generated here and turned into GLSL macro text, so the
// shader is one straight line of compare-exchanges on constant indices.
#include <cstdint>
#include <string>
#include <vector>

#include "base/params.h"
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

// The resolve's sort: insertion (Yang 2010), selection (Carnecky 2013) or the
// unrolled network (also linearized_fragment_buffer's).
enum class Sort { insertion, selection, network };
inline const Choices<Sort> kSorts{
    {Sort::insertion, "insertion"}, {Sort::selection, "selection"}, {Sort::network, "network"}};

// "M(0) M(1) ... M(count-1) ": a macro applied to each constant index, for
// unrolled GLSL (linked_list's network, linearized_fragment_buffer's blocks).
std::string macro_sequence(const std::string& macro, uint32_t count);

// The #defines of algorithms/linked_list/resolve.frag for `sort` and a local
// array of `capacity` elements. For the network they also carry the unrolled
// load, network and blend as macro sequences.
ShaderDefines resolve_defines(Sort sort, uint32_t capacity);

}  // namespace oit::linked_list
