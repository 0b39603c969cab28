#pragma once
// A technique resolved once for a run: looked up in the registry, its
// parameters validated, then created and sized for the run's tile plan.
// Harness::run (bench, pareto, render, ...) and the interactive viewer both
// resolve, check, plan and render a technique through this class, so a
// viewer frame is the frame a bench run renders, and neither repeats the
// other's steps.
#include <functional>
#include <memory>
#include <string>

#include "harness/run/tiling.h"

namespace oit {

class PreparedRun {
 public:
  // Looks `id` up (throws listing the registered ids when unknown) and
  // validates `params` against its schema (throws naming the key and range).
  PreparedRun(const TechniqueRegistry& registry, const std::string& id, const RawParams& params);
  PreparedRun(const PreparedRun&) = delete;
  PreparedRun& operator=(const PreparedRun&) = delete;

  const TechniqueDescriptor& descriptor() const { return descriptor_; }
  const std::string& id() const { return descriptor_.id; }
  // The parameters as the user asked for them (defaults filled in), and as
  // they run: equal until resolve().
  const ParamSet& requested() const { return requested_; }
  const ParamSet& params() const { return params_; }

  // Applies the technique's resolution rule (TechniqueDescriptor::resolve):
  // every `auto` and device- or scene-dependent default becomes the value
  // that runs. Before unsupported(), plan() and create().
  void resolve(const DeviceProfile& device, const SceneFacts& scene, const FrameContent& content);

  // "" when the technique can run on `device` with the scene, otherwise why
  // not (supports()).
  std::string unsupported(const DeviceProfile& device, const SceneFacts& facts) const;
  // The fewest screen tiles whose storage fits `limits`, for a frame of
  // `complexity` (plan_tiles with the technique's storage need and halo).
  TilePlan plan(const DepthComplexity& complexity, const DeviceLimits& limits) const;

  // Creates the technique (again, when it was created before) and sizes it
  // for `plan`: its frame is one tile with the halo, or the whole image.
  void create(TilePlan plan);
  // Moves to a new plan; the technique is resized only when its frame or
  // the tile count changes (then true: its timings start anew). Requires create().
  bool replan(TilePlan plan);
  Technique& technique() const { return *technique_; }
  const Tiling& tiling() const { return *tiling_; }

  // render_frame() of the technique with its tiling.
  ScreenRect render_frame(const Frame& frame, bool record, bool scene_rect,
                          const std::function<void(int)>& after_tile = {}) const;
  // Its counters of the last frame; a tiled frame is rendered once more,
  // not timed, reading them tile by tile (combine_tile_counters).
  TechniqueCounters counters(const Frame& frame, bool scene_rect) const;

 private:
  const TechniqueDescriptor& descriptor_;
  RawParams given_;
  ParamSet requested_;
  ParamSet params_;
  std::unique_ptr<Technique> technique_;
  std::unique_ptr<Tiling> tiling_;
};

}  // namespace oit
