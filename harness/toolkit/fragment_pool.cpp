#include "harness/toolkit/fragment_pool.h"

#include <stdexcept>

#include "harness/gl/check.h"
#include "harness/gl/gl.h"

namespace oit {

FragmentPool::FragmentPool(std::string owner, Sizing sizing, uint64_t largest_record_bytes,
                           std::function<void(uint64_t)> allocate, uint64_t smallest, uint64_t view_texel_bytes)
    : owner_(std::move(owner)),
      sizing_(sizing),
      largest_record_bytes_(largest_record_bytes),
      smallest_(std::max<uint64_t>(smallest, 1)),
      view_texel_bytes_(std::max<uint64_t>(view_texel_bytes, 1)),
      allocate_(std::move(allocate)) {}

void FragmentPool::reset(uint64_t nodes) {
  produced_by_tile_.clear();
  allocate(nodes);
}

void FragmentPool::before_fill(const Frame& frame) {
  produced_by_tile_.resize(size_t(std::max(frame.tile_count, 1)), 0);
  if (sizing_ != Sizing::previous_frame) return;
  const uint64_t most = *std::max_element(produced_by_tile_.begin(), produced_by_tile_.end());
  if (const uint64_t shrunk = fragment_pool::shrunk_capacity(capacity_, most)) allocate(shrunk);
}

void FragmentPool::set_record_bytes(uint64_t largest_record_bytes) {
  if (largest_record_bytes == largest_record_bytes_) return;
  largest_record_bytes_ = largest_record_bytes;
  capacity_ = 0;  // whatever is held has the old layout's size
}

void FragmentPool::set_exact(uint64_t fragments) {
  if (std::max(fragments, smallest_) != capacity_) allocate(fragments);
}

bool FragmentPool::fits(const Frame& frame, uint64_t produced) {
  const size_t tile = size_t(std::max(frame.tile_index, 0));
  if (produced_by_tile_.size() <= tile) produced_by_tile_.resize(tile + 1, 0);
  produced_by_tile_[tile] = produced;
  if (produced <= capacity_) return true;
  // Overflow: nothing is dropped silently; grow to this frame's need and
  // render again (exact sizing only gets here if the count was wrong).
  ++overflow_retries_;
  allocate(sizing_ == Sizing::exact ? produced : fragment_pool::capacity_for(produced));
  return false;
}

uint64_t FragmentPool::fill_until_fits(const Frame& frame, const std::function<void()>& clear,
                                       const std::function<uint64_t()>& fill) {
  for (uint64_t fills = 1;; ++fills) {
    {
      auto stage = frame.clock.stage("clear");
      before_fill(frame);
      clear();
    }
    uint64_t produced = 0;
    {
      auto stage = frame.clock.stage("fill");
      produced = fill();
    }
    if (fits(frame, produced)) return fills;
  }
}

void FragmentPool::allocate(uint64_t capacity) {
  capacity = std::max(capacity, smallest_);
  GLint64 max_block = 0, max_texels = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  glGetInteger64v(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
  const uint64_t bytes = capacity * largest_record_bytes_;
  const uint64_t texels = bytes / view_texel_bytes_;
  if (capacity > 0x7ffffffeull || (max_block > 0 && bytes > uint64_t(max_block)) ||
      (max_texels > 0 && texels > uint64_t(max_texels))) {
    throw std::runtime_error(owner_ + ": a pool of " + std::to_string(capacity) + " fragments (" +
                             std::to_string(bytes >> 20) + " MiB in its largest buffer) exceeds the device's largest "
                             "storage buffer (" + std::to_string(max_block >> 20) + " MiB) or buffer texture (" +
                             std::to_string(max_texels) + " texels); a smaller --memory-budget tiles the frame finer");
  }
  capacity_ = capacity;  // before the callback: the technique's views may ask for it
  allocate_(capacity);
  gl_check("allocating the " + owner_ + " fragment pool of " + std::to_string(capacity) + " nodes");
}

}  // namespace oit
