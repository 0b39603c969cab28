#pragma once
// The fill (carnecky2013 Algorithm 1, pastyrik2016 Algorithm 1) into the
// storage the frame's plan names: linked lists in a pool sized from the
// previous frame (stage "clear", then "fill", again after an overflow);
// exact ranges from a counting pass (stages "count", "fill"); or per-pixel
// arrays of the slots the last frame's longest list sized (stage "fill",
// again with more slots, or into exact ranges, when a list outgrew them).
// With the ranged storages it also keeps each pixel's range, the covered
// pixels, and the cursors the fragments take their slots from.
#include <cstdint>
#include <optional>
#include <vector>

#include "algorithms/illustration_buffer/dispatch.h"
#include "algorithms/illustration_buffer/frame_params.h"
#include "algorithms/illustration_buffer/frame_plan.h"
#include "algorithms/illustration_buffer/records.h"
#include "harness/toolkit/list_length_pass.h"
#include "harness/toolkit/technique.h"

namespace oit::illustration_buffer {

class FillStage {
 public:
  FillStage(const Settings& settings, Records& records, FrameParams& params);
  void resize(int width, int height);
  // The storage this frame fills (FramePlan::storage): storage=arrays_when_even
  // fills arrays where this tile's last frame had lists whose slots
  // (pixels x longest) held at most kMostSlotsPerFragment times its fragments.
  FillStorage planned_storage(const Frame& frame) const;
  FillResult run(const Frame& frame, const FramePlan& plan);

  // The dispatch of the later passes over this frame's stored fragments and covered pixels.
  Grid grid(const FillResult& result) const;
  // The sort's reading of the fill's ranges (sort.comp, IB_OFFSETS_UNIT):
  // linearized's offsets, or the arrays' counts, which are the kept lengths
  // (head, count) unless a list was truncated.
  GLuint offsets_view(const FillResult& result) const;
  // After the sort of exact ranges: throws when a pixel's fill did not end
  // at the end of its counted range (the counting pass and the fill disagreed).
  void check_ranges(const FillResult& result) const;

  uint64_t slot_overflows() const { return slot_overflows_; }
  uint64_t covered_pixels() const { return covered_pixels_.size(); }
  bool fetches_cursors() const { return s_.fetches_cursors(); }

 private:
  void fill_linked(const Frame& frame, const FramePlan& plan, FillResult& result);
  void fill_linearized(const Frame& frame, const FramePlan& plan, FillResult& result);
  void fill_arrays(const Frame& frame, const FramePlan& plan, FillResult& result);
  template <class Count>
  void start_exact_ranges(const Frame& frame, const std::vector<Count>& counts, uint32_t longest, FillResult& result);
  template <class Count>
  void upload_ranges(const std::vector<Count>& counts, bool truncated, bool arrays, FillResult& result);
  void draw_fill(const Frame& frame, const Program& program);
  void remember_lists(const FramePlan& plan, const FillResult& result);
  void size_slots();
  void allocate_slots(uint32_t slots);
  const Program& program(const FramePlan& plan, bool arrays) const { return programs_[arrays][plan.flat_records]; }

  const Settings& s_;
  Records& records_;
  FrameParams& params_;
  // programs_[arrays][flat]: into per-pixel arrays (IB_ARRAYS) or not; with
  // flat_color_records (no colour in the record: fill.frag) or not.
  Program programs_[2][2];
  Framebuffer no_attachments_;
  int width_ = 0, height_ = 0;
  // storage=linearized: the counting pass; linearized and arrays: the fill's
  // ranges (offsets_: linearized's offsets, W*H + 1 values, or arrays'
  // counts) and cursors (a buffer, or the R32UI target with framebuffer fetch).
  std::optional<ListLengthPass> list_lengths_;
  std::optional<SlotCursors> cursors_;
  Buffer offsets_, covered_;
  Texture offsets_view_, covered_view_;
  // covered_pixels_: the pixels holding a fragment, in raster order (covered_, pixel_dispatch.glsl).
  std::vector<uint32_t> host_offsets_, host_sorted_offsets_, host_lengths_, covered_pixels_;
  // Per-pixel arrays: the slots per pixel, each tile's last longest list and
  // fragments (size_slots, planned_storage), and the fills run again for a longer list.
  uint32_t slots_ = 0;
  struct TileLists {
    uint32_t longest = 0;
    uint64_t fragments = 0;
  };
  std::vector<TileLists> lists_by_tile_;
  uint64_t slot_overflows_ = 0;
};

}  // namespace oit::illustration_buffer
