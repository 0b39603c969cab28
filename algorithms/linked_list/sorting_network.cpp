#include "algorithms/linked_list/sorting_network.h"

#include <bit>
#include <stdexcept>

namespace oit::linked_list {

std::vector<Comparator> odd_even_merge_sort(uint32_t size) {
  if (size == 0) throw std::invalid_argument("linked_list: a sorting network needs at least one element");
  const uint32_t padded = std::bit_ceil(size);
  std::vector<Comparator> network;
  // Iterative Batcher odd-even merge sort: merges sorted runs of length
  // `run` into runs of 2*run; `gap` walks the merge's comparator distances.
  for (uint32_t run = 1; run < padded; run <<= 1) {
    for (uint32_t gap = run; gap >= 1; gap >>= 1) {
      for (uint32_t block = gap % run; block + gap < padded; block += 2 * gap) {
        for (uint32_t i = 0; i < gap && block + i + gap < padded; ++i) {
          const uint32_t first = block + i, second = block + i + gap;
          // Only compare within one pair of runs being merged.
          if (first / (2 * run) != second / (2 * run)) continue;
          if (second < size) network.push_back({first, second});
        }
      }
    }
  }
  return network;
}

void apply_network(const std::vector<Comparator>& network, std::vector<uint32_t>& values) {
  for (const Comparator& c : network) {
    if (values.at(c.second) < values.at(c.first)) std::swap(values[c.first], values[c.second]);
  }
}

std::string macro_sequence(const std::string& macro, uint32_t count) {
  std::string text;
  for (uint32_t i = 0; i < count; ++i) text += macro + "(" + std::to_string(i) + ") ";
  return text;
}

ShaderDefines resolve_defines(Sort sort, uint32_t capacity) {
  if (capacity == 0) throw std::invalid_argument("linked_list: the resolve needs room for at least one fragment");
  ShaderDefines defines = {{"LL_CAPACITY", std::to_string(capacity)}};
  switch (sort) {
    case Sort::insertion: defines.push_back({"LL_SORT_INSERTION", "1"}); break;
    case Sort::selection: defines.push_back({"LL_SORT_SELECTION", "1"}); break;
    case Sort::network: {
      defines.push_back({"LL_SORT_NETWORK", "1"});
      std::string network;
      for (const Comparator& c : odd_even_merge_sort(capacity))
        network += "LL_CE(" + std::to_string(c.first) + "," + std::to_string(c.second) + ") ";
      defines.push_back({"LL_LOAD_ALL", macro_sequence("LL_LOAD", capacity)});
      defines.push_back({"LL_NETWORK", network});
      defines.push_back({"LL_BLEND_ALL", macro_sequence("LL_BLEND", capacity)});
      break;
    }
  }
  return defines;
}

}  // namespace oit::linked_list
