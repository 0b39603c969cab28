#pragma once
// The illustration buffer itself, which every stage reads or writes: each
// pixel's head and count, the fill records (fragData), the sorted records
// (fragData2, fragData3), the fill's links and counters, the ground truth,
// the pool that sizes the per-fragment buffers, and their read-only views.
// After the sort fragData's records are dead, and two ranges of it hold the
// diffusion's fields (bind_fields).
#include <algorithm>
#include <cstdint>
#include <vector>

#include "algorithms/illustration_buffer/accuracy.h"
#include "algorithms/illustration_buffer/settings.h"
#include "harness/toolkit/fragment_pool.h"
#include "harness/gl/handles.h"

namespace oit::illustration_buffer {

constexpr GLsizeiptr kFragmentBytes = 48, kNextBytes = 4, kTruthBytes = 16, kFieldBytes = 16;
constexpr GLsizeiptr kDistanceBytes = 4;  // the sweeps' hop distances (sweep_distances.glsl)
// The sorted records, split over fragData2 (key, geometry) and fragData3 (colour, links).
constexpr GLsizeiptr kSearchBytes = 32, kShadeBytes = 32;
// The largest per-record buffer (fragData; it also holds both field ranges) bounds the pool.
constexpr GLsizeiptr kLargestRecordBytes = std::max({kFragmentBytes, kSearchBytes, kShadeBytes, 2 * kFieldBytes});
constexpr GLsizeiptr kCounterBytes = 20;  // produced, longest, dropped, truncated, allocated
// A worklist (worklist.glsl): indirect-dispatch arguments and count, then one entry per pixel.
constexpr GLsizeiptr kWorklistHeaderBytes = 16;
// Keeps both field ranges inside fragData for any storage-offset alignment up to 4 KiB.
constexpr uint64_t kSmallestPool = 256;
// Settings::arrays_where_even: per-pixel arrays only where their slots
// (pixels x longest list) hold at most this many times the fragments; more
// uneven lists (a few deep pixels) take the counting pass and exact ranges.
constexpr uint64_t kMostSlotsPerFragment = 4;

// Bytes per pool record and per pixel of every stage's buffers (storage_need, counters).
uint64_t bytes_per_fragment(const Settings& s);
uint64_t bytes_per_pixel(const Settings& s);

class Records {
 public:
  explicit Records(const Settings& settings);
  Records(const Records&) = delete;
  Records& operator=(const Records&) = delete;

  void resize(int width, int height);
  FragmentPool& pool() { return pool_; }
  const FragmentPool& pool() const { return pool_; }
  uint64_t capacity() const { return pool_.capacity(); }

  // The fill's and the sort's storage buffers at their binding points.
  void bind_storage() const;
  // The sorted records and ranges as the later passes read them (views.glsl).
  void bind_sorted_views() const;
  // The field ranges of `stored` fragments (fields.glsl): read `in`, write `out`.
  void bind_fields(GLintptr in, GLintptr out, uint64_t stored) const;
  // Start of the second field range in fragData: aligned for both the SSBO
  // range binding and the buffer-texture view.
  GLintptr second_field_range() const;
  // Copies the field range at `from` over the one at `to` (`stored` fragments).
  void copy_fields(GLintptr from, GLintptr to, uint64_t stored) const;
  // The last frame's per-pixel ranges and `stored` sorted records (read back).
  void read_lists(uint64_t stored, std::vector<uint32_t>& first, std::vector<uint32_t>& count,
                  std::vector<SortedRecord>& sorted) const;
  std::vector<uint32_t> read_counts() const;
  std::vector<TruthRecord> read_truth(uint64_t produced) const;

  Buffer counters, head, count;
  Texture head_view, count_view, fragment_view;

 private:
  void allocate(uint64_t capacity);

  const Settings& s_;
  int width_ = 0, height_ = 0;
  Buffer next_, data_, data2_, data3_, truth_;
  Texture search_view_, shade_view_, fields_view_[2];
  FragmentPool pool_;
};

}  // namespace oit::illustration_buffer
