#version 450 core
// Work-efficient exclusive prefix sum (Blelloch 1990), one level of
// prefix_sum.h. PS_SCAN: each workgroup scans LFB_SCAN_BLOCK values in
// place, four per invocation serially and the invocations' totals by the
// up-sweep / down-sweep of a balanced tree in shared memory (2(n-1) adds for
// n totals, not n log n), and writes its block's total to ps_sums. PS_ADD:
// adds the scanned block totals of the level above to every value.
// PS_FROM_COUNTS: the level-0 values are read from the R32F per-pixel count
// target of harness/toolkit/list_length_pass.h (pixel i at (i % width, i / width);
// index width*height and beyond are 0) instead of ps_values; that level
// also writes each pixel's count as a uint (ps_lengths) and raises
// ps_longest to the largest count, so that the host reads back two words
// (the total and the longest list), not the whole count target.
#include "algorithms/linearized_fragment_buffer/bindings.h"

#define PS_THREADS 256u
#define PS_ITEMS 4u
layout(local_size_x = 256) in;

layout(std430, binding = LFB_PREFIX_SUM_VALUES_BINDING) buffer PrefixSumValues { uint ps_values[]; };
layout(std430, binding = LFB_PREFIX_SUM_SUMS_BINDING) buffer PrefixSumSums { uint ps_sums[]; };
layout(location = LFB_PREFIX_SUM_COUNT_LOCATION) uniform uint u_count;  // values at this level
#if defined(PS_FROM_COUNTS)
layout(binding = LFB_PREFIX_SUM_COUNTS_UNIT) uniform sampler2D u_counts;
layout(std140, binding = LFB_PREFIX_SUM_PARAMS_BLOCK) uniform PrefixSumBlock { PrefixSumParams ps; };
layout(std430, binding = LFB_PREFIX_SUM_LENGTHS_BINDING) writeonly buffer PrefixSumLengths { uint ps_lengths[]; };
layout(std430, binding = LFB_PREFIX_SUM_LONGEST_BINDING) buffer PrefixSumLongest { uint ps_longest; };
shared uint ps_group_longest;
#endif

uint value_at(uint i) {
#if defined(PS_FROM_COUNTS)
  // Blended counts are whole numbers below 2^24: exact in float.
  return i < ps.pixels ? uint(texelFetch(u_counts, ivec2(int(i) % ps.width, int(i) / ps.width), 0).x) : 0u;
#else
  return i < u_count ? ps_values[i] : 0u;
#endif
}

#if defined(PS_SCAN)
shared uint ps_tree[PS_THREADS];

void main() {
  const uint first = gl_WorkGroupID.x * PS_THREADS * PS_ITEMS + gl_LocalInvocationID.x * PS_ITEMS;
  const uint t = gl_LocalInvocationID.x;
#if defined(PS_FROM_COUNTS)
  if (t == 0u) ps_group_longest = 0u;
  barrier();
#endif
  uint items[PS_ITEMS];
  uint running = 0u, longest = 0u;
  for (uint k = 0u; k < PS_ITEMS; ++k) {
    items[k] = running;  // exclusive within the invocation
    const uint value = value_at(first + k);
    running += value;
    longest = max(longest, value);
#if defined(PS_FROM_COUNTS)
    if (first + k < ps.pixels) ps_lengths[first + k] = value;
#endif
  }
  ps_tree[t] = running;
#if defined(PS_FROM_COUNTS)
  if (longest > 0u) atomicMax(ps_group_longest, longest);
#endif
  barrier();
  // Up-sweep: node (t+1)*2d-1 sums its subtree.
  for (uint d = 1u; d < PS_THREADS; d <<= 1) {
    const uint right = (t + 1u) * 2u * d - 1u;
    if (right < PS_THREADS) ps_tree[right] += ps_tree[right - d];
    barrier();
  }
  const uint block_total = ps_tree[PS_THREADS - 1u];
  barrier();
  if (t == 0u) ps_tree[PS_THREADS - 1u] = 0u;
  barrier();
  // Down-sweep: every node passes its prefix to its left child and
  // prefix + left subtree to its right child.
  for (uint d = PS_THREADS >> 1; d >= 1u; d >>= 1) {
    const uint right = (t + 1u) * 2u * d - 1u;
    if (right < PS_THREADS) {
      const uint left = ps_tree[right - d];
      ps_tree[right - d] = ps_tree[right];
      ps_tree[right] += left;
    }
    barrier();
  }
  const uint before = ps_tree[t];
  for (uint k = 0u; k < PS_ITEMS; ++k) {
    if (first + k < u_count) ps_values[first + k] = before + items[k];
  }
  if (t == 0u) ps_sums[gl_WorkGroupID.x] = block_total;
#if defined(PS_FROM_COUNTS)
  // ps_group_longest is complete: every atomicMax came before the up-sweep's barriers.
  if (t == 0u && ps_group_longest > 0u) atomicMax(ps_longest, ps_group_longest);
#endif
}
#elif defined(PS_ADD)
void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i < u_count) ps_values[i] += ps_sums[i / (PS_THREADS * PS_ITEMS)];
}
#else
#error "prefix_sum.comp: define PS_SCAN or PS_ADD"
#endif
