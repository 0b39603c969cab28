#pragma once
// The prefix sum of the linearized fragment buffer: per-pixel fragment
// counts (the R32F target of harness/toolkit/list_length_pass.h) into per-pixel offsets.
// On the GPU: a work-efficient scan (prefix_sum.comp) of 1024 values per
// workgroup, applied recursively to the workgroups' totals and added back,
// so any number of pixels takes O(n) work in a few dispatches (two levels up
// to 1M pixels, three up to 1G); the first level also writes the lengths
// and the longest list, so the host reads back two words. On the host: a
// running sum over the counts the counting pass has read back anyway,
// uploaded (README: scan).
#include <cstdint>
#include <vector>

#include "harness/gl/handles.h"
#include "harness/gl/uniform_block.h"
#include "algorithms/linearized_fragment_buffer/bindings.h"

namespace oit::lfb {

class PrefixSum {
 public:
  // Values per workgroup: 256 invocations of 4 values (prefix_sum.comp).
  static constexpr uint64_t kBlock = 1024;

  PrefixSum();
  // For the offsets of `pixels` pixels: pixels + 1 values, the last one the total.
  void resize(uint64_t pixels);
  // offsets[i] = the sum of counts[0..i) for i in [0, pixels], pixels in rows
  // of `width` from the bottom. `offsets` holds pixels + 1 uints; `lengths`
  // (pixels uints) gets every count as a uint.
  void scan_counts(const Texture& counts, int width, const Buffer& offsets, const Buffer& lengths);
  // What the last scan_counts found: the total (offsets[pixels]) and the
  // largest count, read back (two words; waits for the scan).
  struct Summary {
    uint64_t total = 0;
    uint32_t longest = 0;
  };
  Summary read_summary(const Buffer& offsets) const;
  // The same offsets summed on the host from `counts` (ListLengthPass::host_counts,
  // `pixels` values) and uploaded into `offsets`.
  void scan_host_counts(const std::vector<float>& counts, const Buffer& offsets);
  // The workgroup totals of every level and the longest-list word.
  uint64_t bytes_allocated() const;

 private:
  void dispatch(GLuint program, const Buffer& values, uint64_t count, const Buffer& sums, uint64_t groups);

  Program scan_counts_, scan_, add_;
  UniformBlock<PrefixSumParams> params_{LFB_PREFIX_SUM_PARAMS_BLOCK};
  uint64_t pixels_ = 0;
  // Level k scans levels_[k] values in blocks; their totals go to sums_[k],
  // which level k+1 scans in place. The last level is one block.
  std::vector<uint64_t> levels_;
  std::vector<Buffer> sums_;
  Buffer longest_;
  std::vector<uint32_t> host_offsets_;
};

}  // namespace oit::lfb
