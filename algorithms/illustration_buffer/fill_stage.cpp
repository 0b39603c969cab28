#include "algorithms/illustration_buffer/fill_stage.h"

#include <algorithm>

#include "algorithms/illustration_buffer/bindings.h"
#include "algorithms/illustration_buffer/shader_variant.h"
#include "harness/toolkit/passes.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"

namespace oit::illustration_buffer {

FillStage::FillStage(const Settings& s, Records& records, FrameParams& params)
    : s_(s), records_(records), params_(params) {
  if (s_.linearized()) list_lengths_.emplace();
  if (s_.ranged()) cursors_.emplace(s_.fill);
  for (const bool arrays : {false, true}) {
    if (arrays ? !s_.may_fill_arrays() : s_.arrays()) continue;
    for (const bool flat : {false, true}) {
      if (flat && !s_.flat_color_records) continue;
      ShaderVariant v;
      v.ranged = s_.ranged();
      v.arrays = arrays;
      v.fetch_cursor = s_.fetches_cursors();
      v.flat_color = flat;
      v.measure = s_.measure_accuracy;
      v.surface = s_.records_surface();
      v.angle = s_.modulation == Modulation::angle;
      v.normal_variation = s_.modulation == Modulation::normal_variation;
      programs_[arrays][flat] = build_geometry_program("algorithms/illustration_buffer/fill.frag", v.defines());
    }
  }
}

void FillStage::resize(int width, int height) {
  width_ = width;
  height_ = height;
  slots_ = s_.arrays() ? uint32_t(s_.initial_nodes_per_pixel) : 0;  // arrays_where_even: sized on its first arrays frame
  lists_by_tile_.clear();
  no_attachments_ = make_attachmentless_framebuffer(width, height);
  if (!s_.ranged()) return;
  const GLsizeiptr pixels = GLsizeiptr(width) * height;
  if (list_lengths_) list_lengths_->resize(width, height);
  offsets_ = make_buffer((pixels + 1) * 4);
  offsets_view_ = make_buffer_texture(offsets_, GL_R32UI, 0, (pixels + 1) * 4);
  covered_ = make_buffer(pixels * 4);
  covered_view_ = make_buffer_texture(covered_, GL_R32UI, 0, pixels * 4);
  cursors_->resize(width, height, "illustration_buffer");
  gl_check("allocating the illustration buffer's per-pixel ranges");
}

FillStorage FillStage::planned_storage(const Frame& frame) const {
  if (s_.arrays()) return FillStorage::arrays;
  if (!s_.arrays_where_even) return s_.linearized() ? FillStorage::linearized : FillStorage::linked;
  const size_t tile = size_t(std::max(frame.tile_index, 0));
  if (tile >= lists_by_tile_.size()) return FillStorage::linearized;  // no history: the counting pass first
  const TileLists& last = lists_by_tile_[tile];
  const uint64_t slots = uint64_t(width_) * uint64_t(height_) * last.longest;
  return last.fragments > 0 && slots <= kMostSlotsPerFragment * last.fragments ? FillStorage::arrays
                                                                               : FillStorage::linearized;
}

FillResult FillStage::run(const Frame& frame, const FramePlan& plan) {
  lists_by_tile_.resize(size_t(std::max(plan.tiles, 1)));
  FillResult result;
  result.storage = plan.storage;
  switch (plan.storage) {
    case FillStorage::linked: fill_linked(frame, plan, result); break;
    case FillStorage::linearized: fill_linearized(frame, plan, result); break;
    case FillStorage::arrays: fill_arrays(frame, plan, result); break;
  }
  return result;
}

Grid FillStage::grid(const FillResult& result) const {
  return {width_, height_, result.stored, s_.ranged(), covered_view_.id(), covered_pixels_.size()};
}

GLuint FillStage::offsets_view(const FillResult& result) const {
  return result.arrays() && result.truncated_lists == 0 ? records_.count_view.id() : offsets_view_.id();
}

void FillStage::check_ranges(const FillResult& result) const {
  // The sort's dispatch left out the empty pixels: the host checks every range.
  if (result.linearized())
    fail_on_mismatched_ranges("illustration_buffer", cursors_->count_mismatched(host_offsets_), result.produced);
}

// storage=linked: stage "clear", then the fill into linked lists, again
// after a pool overflow (the pool grew).
void FillStage::fill_linked(const Frame& frame, const FramePlan& plan, FillResult& result) {
  GLuint counts[5] = {};  // produced, longest, dropped, truncated, allocated
  const auto clear = [&] {
    fill_buffer_u32(records_.head, IB_NIL);
    fill_buffer_u32(records_.count, 0);
    fill_buffer_u32(records_.counters, 0);
  };
  const auto fill = [&]() -> uint64_t {
    params_.values.capacity = uint32_t(records_.capacity());
    params_.upload();
    records_.bind_storage();
    draw_scene_pass(frame, program(plan, false), no_attachments_);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    glGetNamedBufferSubData(records_.counters.id(), 0, sizeof(counts), counts);
    return counts[0];
  };
  result.passes = records_.pool().fill_until_fits(frame, clear, fill);
  result.produced = counts[0];
  result.dropped = counts[2];
  result.truncated_lists = counts[3];
  result.stored = result.produced - result.dropped;
  result.longest = counts[1];
}

// storage=linearized: stage "count" (the counting pass, the ranges from
// its counts, the pool sized exactly, the cursors started), then stage "fill".
void FillStage::fill_linearized(const Frame& frame, const FramePlan& plan, FillResult& result) {
  {
    auto stage = frame.clock.stage("count");
    result.longest = list_lengths_->longest_list(frame);
    start_exact_ranges(frame, list_lengths_->host_counts(), result.longest, result);
  }
  auto stage = frame.clock.stage("fill");
  draw_fill(frame, program(plan, false));
  result.passes = 2;
  remember_lists(plan, result);
}

// The ranges of storage=linearized from every pixel's count, the pool
// sized exactly and the cursors at the offsets.
template <class Count>
void FillStage::start_exact_ranges(const Frame& frame, const std::vector<Count>& counts, uint32_t longest,
                                   FillResult& result) {
  upload_ranges(counts, longest > s_.max_per_pixel, false, result);
  records_.pool().before_fill(frame);
  records_.pool().set_exact(result.produced);
  cursors_->start(offsets_);
}

// The fill of ranged storage: the scene drawn, each fragment at its pixel's cursor.
void FillStage::draw_fill(const Frame& frame, const Program& fill) {
  params_.values.slots = slots_;
  params_.upload();
  records_.bind_storage();
  cursors_->bind_image(IB_CURSORS_IMAGE_UNIT);
  draw_scene_pass(frame, fill, cursors_->fill_framebuffer());
  SlotCursors::unbind_image(IB_CURSORS_IMAGE_UNIT);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

// From the counted lengths (the counting pass's floats, or the arrays'
// final cursors): the fill's ranges (offsets_, linearized), and the sorted
// ranges and lengths of the kept fragments (head, count: the prefix sum
// of min(count, max_per_pixel), the fill's own offsets unless `truncated`).
template <class Count>
void FillStage::upload_ranges(const std::vector<Count>& counts, bool truncated, bool arrays, FillResult& result) {
  offsets_from_counts(counts, host_offsets_);
  if (!arrays) glNamedBufferSubData(offsets_.id(), 0, GLsizeiptr(host_offsets_.size() * 4), host_offsets_.data());
  lengths_from_counts(counts, host_lengths_, s_.max_per_pixel);
  const GLsizeiptr pixel_bytes = GLsizeiptr(host_lengths_.size() * 4);
  glNamedBufferSubData(records_.count.id(), 0, pixel_bytes, host_lengths_.data());
  result.produced = host_offsets_.back();
  result.stored = result.produced;
  result.truncated_lists = 0;
  if (truncated) {
    offsets_from_counts(counts, host_sorted_offsets_, s_.max_per_pixel);
    glNamedBufferSubData(records_.head.id(), 0, pixel_bytes, host_sorted_offsets_.data());
    result.stored = host_sorted_offsets_.back();
    result.truncated_lists =
        uint64_t(std::count_if(counts.begin(), counts.end(), [&](Count n) { return n > Count(s_.max_per_pixel); }));
  } else {
    glNamedBufferSubData(records_.head.id(), 0, pixel_bytes, host_offsets_.data());
  }
  result.dropped = result.produced - result.stored;
  // Every pixel written, the end advanced past the covered ones: no branch
  // to mispredict on half-covered images.
  covered_pixels_.resize(host_lengths_.size());
  size_t covered = 0;
  for (uint32_t p = 0; p < host_lengths_.size(); ++p) {
    covered_pixels_[covered] = p;
    covered += host_lengths_[p] > 0 ? 1 : 0;
  }
  covered_pixels_.resize(covered);
  if (!covered_pixels_.empty())
    glNamedBufferSubData(covered_.id(), 0, GLsizeiptr(covered_pixels_.size() * 4), covered_pixels_.data());
}

// Per-pixel arrays: stage "fill": the fill into arrays of slots_ records,
// the cursors read back (each pixel's count) and the ranges from them. A
// list longer than the slots (its cursor passed them) is an overflow
// retry, nothing is lost: storage=arrays grows the slots to it and fills
// again; arrays_when_even fills again into exact ranges from the counts the
// cursors hold (as after a counting pass), so that a frame whose lists
// turned uneven never sizes arrays by its longest.
void FillStage::fill_arrays(const Frame& frame, const FramePlan& plan, FillResult& result) {
  auto stage = frame.clock.stage("fill");
  size_slots();
  for (result.passes = 1;; ++result.passes) {
    cursors_->start_at_zero();
    draw_fill(frame, program(plan, true));
    const std::vector<uint32_t>& counts = cursors_->read_back();
    result.longest = counts.empty() ? 0 : *std::max_element(counts.begin(), counts.end());
    if (result.longest <= slots_) {
      upload_ranges(counts, result.longest > s_.max_per_pixel, true, result);
      remember_lists(plan, result);
      if (result.truncated_lists > 0)  // the sort's ib_fill_counts; else the kept lengths are the counts
        glNamedBufferSubData(offsets_.id(), 0, GLsizeiptr(counts.size() * 4), counts.data());
      return;
    }
    ++slot_overflows_;
    if (s_.arrays_where_even) {
      result.storage = FillStorage::linearized;  // the fill's outcome: exact ranges
      start_exact_ranges(frame, counts, result.longest, result);
      remember_lists(plan, result);
      draw_fill(frame, program(plan, false));
      result.passes = 2;
      return;
    }
    allocate_slots(result.longest);
  }
}

// This tile's longest list and fragments, for the next frame's plan.
void FillStage::remember_lists(const FramePlan& plan, const FillResult& result) {
  lists_by_tile_[size_t(plan.tile)] = {result.longest, result.produced};
}

// Before a fill into per-pixel arrays: as many slots as the longest list
// any tile of the last frame had (none known: initial_nodes_per_pixel);
// fewer only when that is less than half of them, so that a view whose
// longest list wavers does not reallocate every frame.
void FillStage::size_slots() {
  uint32_t last = 0;
  for (const TileLists& tile : lists_by_tile_) last = std::max(last, tile.longest);
  const uint32_t wanted = last > 0 ? last : uint32_t(s_.initial_nodes_per_pixel);
  if (wanted > slots_ || 2 * wanted < slots_ || records_.capacity() < uint64_t(width_) * uint64_t(height_) * slots_)
    allocate_slots(wanted);
}

void FillStage::allocate_slots(uint32_t slots) {
  slots_ = std::max<uint32_t>(slots, 1);
  records_.pool().reset(uint64_t(width_) * uint64_t(height_) * slots_);
}

}  // namespace oit::illustration_buffer
