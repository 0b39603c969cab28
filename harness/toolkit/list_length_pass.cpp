#include "harness/toolkit/list_length_pass.h"

#include <algorithm>
#include <stdexcept>

#include "harness/toolkit/passes.h"
#include "harness/gl/check.h"
#include "harness/gl/context.h"
#include "harness/gl/shader_program.h"

namespace oit {

// How the counts are made and reduced, measured on llvmpipe (32-layer
// quads, 256x256, medians of 5 frames, wall clock): an atomicAdd per
// fragment into an SSBO plus an atomicMax into one word (only when the new
// count exceeds it) took 13-16 ms; imageAtomicAdd on an R32UI image plus the
// same atomicMax 17-18 ms; additive blending into R32F, reading the 256 KiB
// back and taking the maximum on the CPU 1.8 ms. Blending needs no atomics
// and llvmpipe blends a whole tile at once, so it is used.
ListLengthPass::ListLengthPass() : program_(build_geometry_program("shaders/count_fragments_blend.frag")) {}

void ListLengthPass::resize(int width, int height) {
  width_ = width;
  height_ = height;
  counts_ = make_texture_2d(GL_R32F, width, height);
  framebuffer_ = make_framebuffer();
  glNamedFramebufferTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT0, counts_.id(), 0);
  if (glCheckNamedFramebufferStatus(framebuffer_.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw GlError("list-length pass: R32F count framebuffer is incomplete");
  readback_.assign(size_t(width) * size_t(height), 0.0f);
  gl_check("allocating the list-length counters");
}

void ListLengthPass::draw(const Frame& frame) {
  const float zero = 0.0f;
  glClearTexImage(counts_.id(), 0, GL_RED, GL_FLOAT, &zero);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glViewport(0, 0, width_, height_);
  glDisable(GL_DEPTH_TEST);  // every fragment counts
  glDisable(GL_CULL_FACE);
  glUseProgram(program_.id());
  frame.set_shared_uniforms(program_.id());
  glEnablei(GL_BLEND, 0);
  glBlendEquationi(0, GL_FUNC_ADD);
  glBlendFunci(0, GL_ONE, GL_ONE);
  frame.scene.draw();
  glDisable(GL_BLEND);
  gl_check("list-length counting pass");
}

uint32_t ListLengthPass::longest_list(const Frame& frame) {
  draw(frame);
  return read_back();
}

uint32_t ListLengthPass::read_back() {
  glGetTextureImage(counts_.id(), 0, GL_RED, GL_FLOAT, GLsizei(readback_.size() * sizeof(float)), readback_.data());
  gl_check("reading the list lengths back");
  float longest = 0.0f;
  total_ = 0;
  for (const float count : readback_) {
    longest = std::max(longest, count);
    total_ += uint64_t(count);
  }
  return uint32_t(longest);
}

SlotFill resolve_slot_fill(SlotFill requested, const DeviceProfile& device) {
  if (requested != SlotFill::automatic) return requested;
  return device.framebuffer_fetch ? SlotFill::framebuffer_fetch : SlotFill::atomic;
}

bool fills_by_framebuffer_fetch(SlotFill fill) {
  if (fill == SlotFill::automatic) throw std::logic_error("fill=auto reached a technique unresolved (resolve_slot_fill)");
  return fill == SlotFill::framebuffer_fetch;
}

std::string missing_slot_fill_feature(SlotFill fill, const DeviceProfile& device) {
  if (fill == SlotFill::framebuffer_fetch && !device.framebuffer_fetch)
    return "fill=framebuffer_fetch needs GL_EXT_shader_framebuffer_fetch, which this device lacks (use fill=atomic or "
           "auto)";
  return "";
}

void SlotCursors::resize(int width, int height, const std::string& owner) {
  width_ = width;
  height_ = height;
  const GLsizeiptr bytes = GLsizeiptr(width) * height * 4;
  if (fetch_) {
    target_ = make_texture_2d(GL_R32UI, width, height);
    framebuffer_ = make_target_framebuffer({&target_}, owner + ": cursor target (R32UI)");
  } else {
    buffer_ = make_buffer(bytes);
    view_ = make_buffer_texture(buffer_, GL_R32UI, 0, bytes);
    framebuffer_ = make_attachmentless_framebuffer(width, height);
  }
  gl_check(owner + ": allocating the fill's cursors");
}

void SlotCursors::start(const Buffer& offsets) const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT);
  if (!fetch_) {
    glCopyNamedBufferSubData(offsets.id(), buffer_.id(), 0, 0, GLsizeiptr(width_) * height_ * 4);
    return;
  }
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, offsets.id());
  glTextureSubImage2D(target_.id(), 0, 0, 0, width_, height_, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
}

void SlotCursors::start_at_zero() const {
  const GLuint zero = 0;
  if (fetch_) glClearTexImage(target_.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  else glClearNamedBufferData(buffer_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

const std::vector<uint32_t>& SlotCursors::read_back() const {
  const size_t pixels = size_t(width_) * size_t(height_);
  ends_.resize(pixels);
  const GLsizei bytes = GLsizei(pixels * sizeof(uint32_t));
  if (fetch_) {
    glGetTextureImage(target_.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, bytes, ends_.data());
  } else {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(buffer_.id(), 0, bytes, ends_.data());
  }
  gl_check("reading the fill's final cursors back");
  return ends_;
}

uint32_t SlotCursors::count_mismatched(const std::vector<uint32_t>& offsets) const {
  const size_t pixels = size_t(width_) * size_t(height_);
  if (offsets.size() != pixels + 1)
    throw std::logic_error("SlotCursors::count_mismatched: " + std::to_string(offsets.size()) + " offsets for " +
                           std::to_string(pixels) + " pixels");
  const std::vector<uint32_t>& ends = read_back();
  uint32_t mismatched = 0;
  for (size_t p = 0; p < pixels; ++p) mismatched += ends[p] != offsets[p + 1] ? 1 : 0;
  return mismatched;
}

void SlotCursors::bind_image(GLuint unit) const {
  if (!fetch_) glBindImageTexture(unit, view_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
}

void SlotCursors::unbind_image(GLuint unit) { glBindImageTexture(unit, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI); }

void fail_on_mismatched_ranges(const std::string& technique, uint32_t mismatched, uint64_t counted_fragments) {
  if (mismatched != 0)
    throw std::runtime_error(technique + ": in " + std::to_string(mismatched) +
                             " pixels the fill produced another number of fragments than the counting pass counted (" +
                             std::to_string(counted_fragments) + " in all); the image would be wrong");
}

namespace {

// offsets_from_counts for whole-number counts of any type (float from the
// counting pass's R32F target, uint from a fill's cursors).
template <class Count>
void offsets_from(const std::vector<Count>& counts, std::vector<uint32_t>& offsets, uint32_t most_per_pixel) {
  offsets.resize(counts.size() + 1);
  uint64_t sum = 0;
  for (size_t i = 0; i < counts.size(); ++i) {
    offsets[i] = uint32_t(sum);
    sum += std::min(uint64_t(counts[i]), uint64_t(most_per_pixel));  // whole numbers below 2^24 when float: exact
    if (sum > UINT32_MAX)
      throw std::runtime_error("list lengths: more than " + std::to_string(UINT32_MAX) +
                               " fragments in one frame overflow 32-bit offsets");
  }
  offsets.back() = uint32_t(sum);
}

template <class Count>
void lengths_from(const std::vector<Count>& counts, std::vector<uint32_t>& lengths, uint32_t most_per_pixel) {
  lengths.resize(counts.size());
  for (size_t i = 0; i < counts.size(); ++i) lengths[i] = std::min(uint32_t(counts[i]), most_per_pixel);
}

}  // namespace

void offsets_from_counts(const std::vector<float>& counts, std::vector<uint32_t>& offsets, uint32_t most_per_pixel) {
  offsets_from(counts, offsets, most_per_pixel);
}

void offsets_from_counts(const std::vector<uint32_t>& counts, std::vector<uint32_t>& offsets, uint32_t most_per_pixel) {
  offsets_from(counts, offsets, most_per_pixel);
}

void lengths_from_counts(const std::vector<float>& counts, std::vector<uint32_t>& lengths, uint32_t most_per_pixel) {
  lengths_from(counts, lengths, most_per_pixel);
}

void lengths_from_counts(const std::vector<uint32_t>& counts, std::vector<uint32_t>& lengths, uint32_t most_per_pixel) {
  lengths_from(counts, lengths, most_per_pixel);
}

uint64_t ListLengthPass::bytes_allocated() const { return uint64_t(width_) * uint64_t(height_) * 4u; }

void check_slots_fit(const std::string& technique, int k, int width, int height, uint64_t largest_buffer_bytes,
                     const std::string& buffer) {
  GLint64 max_block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  if (max_block <= 0 || largest_buffer_bytes <= uint64_t(max_block)) return;
  throw std::runtime_error(technique + ": k=" + std::to_string(k) + " at " + std::to_string(width) + "x" +
                           std::to_string(height) + " needs " + std::to_string(largest_buffer_bytes >> 20) +
                           " MiB for " + buffer + ", more than the device's largest storage block (" +
                           std::to_string(max_block >> 20) + " MiB); lower k or the size");
}

int slots_per_pixel_cap(int width, int height, uint64_t memory_cap_bytes, uint64_t bytes_per_slot,
                        uint64_t largest_array_bytes_per_slot, int max_slots) {
  const uint64_t pixels = std::max<uint64_t>(uint64_t(width) * uint64_t(height), 1);
  uint64_t cap = memory_cap_bytes / (pixels * bytes_per_slot);
  GLint64 max_block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  if (max_block > 0) cap = std::min(cap, uint64_t(max_block) / (pixels * largest_array_bytes_per_slot));
  return int(std::clamp<uint64_t>(cap, 1, uint64_t(max_slots)));
}

SlotsPerPixel::SlotsPerPixel(const ParamSet& params, int max_k)
    : max_k_(max_k),
      fixed_(params.is_auto("k") ? 0 : int(params.integer("k"))),
      memory_cap_bytes_(uint64_t(params.integer("auto_k_memory_mb")) << 20),
      cap_(max_k) {
  if (params.is_auto("k")) count_pass_.emplace();
}

void SlotsPerPixel::resize(int width, int height, uint64_t bytes_per_slot, uint64_t largest_array_bytes_per_slot) {
  if (!automatic()) return;
  count_pass_->resize(width, height);
  cap_ = slots_per_pixel_cap(width, height, memory_cap_bytes_, bytes_per_slot, largest_array_bytes_per_slot, max_k_);
}

int SlotsPerPixel::for_frame(const Frame& frame) {
  if (!automatic()) return fixed_;
  auto count = frame.clock.stage("count");
  longest_list_ = count_pass_->longest_list(frame);
  return std::clamp(int(std::min<uint32_t>(longest_list_, uint32_t(max_k_))), 1, cap_);
}

void SlotsPerPixel::add_figures(std::vector<Figure>& extra, int k_used) const {
  extra.push_back({"k_used", double(k_used), Combine::max});
  if (!automatic()) return;
  extra.push_back({"longest_list", double(longest_list_), Combine::max});
  extra.push_back({"k_cap", double(cap_), Combine::max});
  extra.push_back({"k_capped", longest_list_ > uint32_t(cap_) ? 1.0 : 0.0, Combine::max});
}

}  // namespace oit
