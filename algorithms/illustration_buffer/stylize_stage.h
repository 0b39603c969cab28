#pragma once
// Stylize (carnecky2013 section 5): the fields' initial and boundary
// conditions (stage "stylize_init") and their diffusion (stage "diffuse"):
// `iterations` synchronous steps of eq. 8-9 over every fragment, or over
// worklists of the pixels that can still change (skip_converged), or sweeps
// of hop distances to the fixed point where that is the steps' result
// (Diffusion). The fields live in two ranges of fragData (Records), the
// distances and the worklists in this stage's buffers.
#include <cstdint>

#include "algorithms/illustration_buffer/dispatch.h"
#include "algorithms/illustration_buffer/frame_params.h"
#include "algorithms/illustration_buffer/frame_plan.h"
#include "algorithms/illustration_buffer/records.h"

namespace oit::illustration_buffer {

class StylizeStage {
 public:
  // Sets the sweeps' table size and cutoffs in `params`.
  StylizeStage(const Settings& settings, Records& records, FrameParams& params);
  void resize(int width, int height);
  // Whether this frame's diffusion sweeps (FramePlan::swept): alpha cannot
  // move when eq. 4 gives every fragment the scene's one alpha. Throws for
  // diffusion=sweep where it cannot.
  bool sweeps(const SceneGpu& scene);
  // Whether every triangle of `scene` has the same alpha (then, with eq. 4,
  // every fragment starts with it: stylize_init.comp). Once per scene.
  bool one_alpha(const SceneGpu& scene);
  void run(const Frame& frame, const FramePlan& plan, const Grid& grid, GLintptr second_range);
  // The compose's input: the sweeps' distances and table, or the field
  // range the last step wrote.
  void bind_result(const FramePlan& plan, const Grid& grid, GLintptr second_range) const;
  // The last frame's dispatches of the stylize stages (counter stylize_passes).
  double passes(const FramePlan& plan) const;
  // The last frame's diffusion work: its sweeps, or its listed steps (read back).
  void append_work(TechniqueCounters& c, const FramePlan& plan, uint64_t stored) const;
  uint64_t bytes_allocated() const;

 private:
  void build_inits();
  void build_field_table(FrameParams& params);
  void start_worklists() const;
  void run_queued(uint32_t step) const;
  void sweep_to_fixed_point(const Grid& grid);

  const Settings& s_;
  Records& records_;
  const FrameParams& params_;
  // init_: the steps without skip_converged (queues nothing); tracked_inits_:
  // with its queue ([1]: also alpha seeds); sweep_init_: the sweeps' distances.
  Program init_, tracked_inits_[2], sweep_init_, seed_queue_;
  // The steps over every fragment, over the listed pixels, a sweep, the sweeps' check.
  Program diffuse_, diffuse_listed_, diffuse_sweep_, sweep_check_;
  int width_ = 0, height_ = 0;
  Buffer stamps_, worklists_[3], pixel_updates_, seeds_;  // skip_converged (worklist.glsl)
  Texture worklist_views_[3], seeds_view_;
  Buffer sweep_changed_;  // 1 when the init found a seed, then when the check found a move
  // Each fragment's hop distances (sized with the pool), and beta and gamma by distance (sweep_distances.glsl).
  Buffer distances_, field_table_;
  Texture distances_view_, field_table_view_;
  uint64_t distances_capacity_ = 0;
  uint32_t field_table_size_ = 0;
  uint64_t sweep_rounds_ = 0;  // the last frame's
  uint64_t one_alpha_scene_ = 0;  // SceneGpu::serial of the scene one_alpha() last saw
  bool one_alpha_ = false;
};

}  // namespace oit::illustration_buffer
