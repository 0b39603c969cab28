#pragma once
// The sort (stage "sort"): each pixel's fill records into a contiguous
// range of sorted records, nearest first (carnecky2013 section 4.3, or
// pastyrik2016 Algorithm 2 with sort=dynamic, or its static arrays with
// sort=static_arrays), with each record's colour
// (the flat colour by triangle id with flat colour records) and, for
// neighbors=triangle_index, its triangle's vertex indices from the triangle
// table this stage keeps per scene.
#include <cstdint>
#include <map>
#include <tuple>

#include "algorithms/illustration_buffer/dispatch.h"
#include "algorithms/illustration_buffer/fill_stage.h"
#include "algorithms/illustration_buffer/frame_plan.h"
#include "algorithms/illustration_buffer/records.h"

namespace oit::illustration_buffer {

// The sort a frame runs, from its plan and its fill's longest list.
struct SortChoice {
  bool dynamic = false;        // pastyrik2016's insertion sort (no array)
  bool static_arrays = false;  // pastyrik2016's static arrays (array: IB_STATIC_ENTRIES)
  uint32_t array = 0;          // the local array's size
  bool truncates = false;      // a list is longer than the array
};

class SortStage {
 public:
  SortStage(const Settings& settings, Records& records);
  // The sort's local array: the frame's longest list rounded up to a power
  // of two (a few programs serve every frame), at most max_per_pixel. The
  // dynamic sort (sort=dynamic) has no array; sort=static_arrays has the paper's
  // IB_STATIC_ENTRIES whatever the lists.
  SortChoice choose(const FillResult& fill) const;
  void run(const Frame& frame, const FramePlan& plan, const FillResult& fill, const SortChoice& choice,
           const FillStage& fill_stage, const Grid& grid);
  uint64_t triangle_rows() const { return triangle_rows_; }
  uint64_t isolated_triangles() const { return isolated_triangles_; }

 private:
  GLuint program(const FramePlan& plan, const FillResult& fill, const SortChoice& choice);
  void prepare_triangles(const SceneGpu& scene);

  const Settings& s_;
  Records& records_;
  // By local array size (0: the dynamic sort), flat colours, whether a list
  // is longer than the array, whether the fill records are per-pixel arrays,
  // and whether the arrays are the static ones.
  using Variant = std::tuple<uint32_t, bool, bool, bool, bool>;
  std::map<Variant, Program> programs_;
  // neighbors=triangle_index: the triangle table (SceneGpu::serial of its scene).
  Buffer triangles_;
  Texture triangles_view_;
  uint64_t triangle_scene_ = 0, triangle_rows_ = 0, isolated_triangles_ = 0;
};

}  // namespace oit::illustration_buffer
