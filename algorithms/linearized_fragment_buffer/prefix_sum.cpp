#include "algorithms/linearized_fragment_buffer/prefix_sum.h"

#include <stdexcept>
#include <string>

#include "harness/toolkit/list_length_pass.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"
#include "harness/gl/uniforms.h"
#include "algorithms/linearized_fragment_buffer/bindings.h"

namespace oit::lfb {
namespace {

constexpr uint64_t kAddGroup = 256;  // prefix_sum.comp's local size

uint64_t blocks_of(uint64_t count) { return (count + PrefixSum::kBlock - 1) / PrefixSum::kBlock; }

}  // namespace

PrefixSum::PrefixSum()
    : scan_counts_(build_compute_program("algorithms/linearized_fragment_buffer/prefix_sum.comp",
                                         {{"PS_SCAN", "1"}, {"PS_FROM_COUNTS", "1"}})),
      scan_(build_compute_program("algorithms/linearized_fragment_buffer/prefix_sum.comp", {{"PS_SCAN", "1"}})),
      add_(build_compute_program("algorithms/linearized_fragment_buffer/prefix_sum.comp", {{"PS_ADD", "1"}})),
      longest_(make_buffer(4)) {}

void PrefixSum::resize(uint64_t pixels) {
  pixels_ = pixels;
  levels_.clear();
  sums_.clear();
  for (uint64_t count = pixels + 1;; count = blocks_of(count)) {
    levels_.push_back(count);
    sums_.push_back(make_buffer(GLsizeiptr(blocks_of(count) * 4)));
    if (blocks_of(count) == 1) break;
  }
  gl_check("allocating the prefix sum's workgroup totals");
}

uint64_t PrefixSum::bytes_allocated() const {
  uint64_t bytes = 4;  // longest_
  for (uint64_t count : levels_) bytes += blocks_of(count) * 4;
  return bytes;
}

void PrefixSum::dispatch(GLuint program, const Buffer& values, uint64_t count, const Buffer& sums, uint64_t groups) {
  glUseProgram(program);
  set_uniform(program, LFB_PREFIX_SUM_COUNT_LOCATION, GLuint(count));
  bind_storage_buffers({{LFB_PREFIX_SUM_VALUES_BINDING, &values}, {LFB_PREFIX_SUM_SUMS_BINDING, &sums}});
  glDispatchCompute(GLuint(groups), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void PrefixSum::scan_counts(const Texture& counts, int width, const Buffer& offsets, const Buffer& lengths) {
  fill_buffer_u32(longest_, 0);
  bind_storage_buffers({{LFB_PREFIX_SUM_LENGTHS_BINDING, &lengths}, {LFB_PREFIX_SUM_LONGEST_BINDING, &longest_}});
  params_.values.width = width;
  params_.values.pixels = GLuint(pixels_);
  params_.upload();
  glBindTextureUnit(LFB_PREFIX_SUM_COUNTS_UNIT, counts.id());
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  // Up: every level scans its blocks and hands their totals to the next.
  for (size_t k = 0; k < levels_.size(); ++k) {
    dispatch(k == 0 ? scan_counts_.id() : scan_.id(), k == 0 ? offsets : sums_[k - 1], levels_[k], sums_[k],
             blocks_of(levels_[k]));
  }
  glBindTextureUnit(LFB_PREFIX_SUM_COUNTS_UNIT, 0);
  // Down: every level adds the scanned totals of the blocks before its own.
  for (size_t k = levels_.size() - 1; k-- > 0;) {
    dispatch(add_.id(), k == 0 ? offsets : sums_[k - 1], levels_[k], sums_[k], (levels_[k] + kAddGroup - 1) / kAddGroup);
  }
  gl_check("prefix sum of the per-pixel fragment counts");
}

PrefixSum::Summary PrefixSum::read_summary(const Buffer& offsets) const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  GLuint total = 0, longest = 0;
  glGetNamedBufferSubData(offsets.id(), GLintptr(pixels_ * 4), 4, &total);
  glGetNamedBufferSubData(longest_.id(), 0, 4, &longest);
  gl_check("reading the prefix sum's total and longest list");
  return {total, longest};
}

void PrefixSum::scan_host_counts(const std::vector<float>& counts, const Buffer& offsets) {
  if (counts.size() != pixels_) throw std::logic_error("prefix sum: the host counts are not one per pixel");
  offsets_from_counts(counts, host_offsets_);
  glNamedBufferSubData(offsets.id(), 0, GLsizeiptr(host_offsets_.size() * 4), host_offsets_.data());
  gl_check("uploading the per-pixel offsets summed on the host");
}

}  // namespace oit::lfb
