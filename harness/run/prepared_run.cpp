#include "harness/run/prepared_run.h"

#include <vector>

#include "harness/gl/check.h"

namespace oit {

PreparedRun::PreparedRun(const TechniqueRegistry& registry, const std::string& id, const RawParams& params)
    : descriptor_(registry.get(id)),
      given_(params),
      requested_(descriptor_.params, params, "technique '" + id + "'"),
      params_(requested_) {}

void PreparedRun::resolve(const DeviceProfile& device, const SceneFacts& scene, const FrameContent& content) {
  params_ = resolve_params(descriptor_, {device, scene, content, given_});
}

std::string PreparedRun::unsupported(const DeviceProfile& device, const SceneFacts& facts) const {
  return supports(descriptor_, params_, device, facts);
}

TilePlan PreparedRun::plan(const DepthComplexity& complexity, const DeviceLimits& limits) const {
  std::function<StorageNeed(const FrameContent&)> need;
  if (descriptor_.storage_need)
    need = [this](const FrameContent& content) { return descriptor_.storage_need(params_, content); };
  const int halo = descriptor_.tile_halo ? descriptor_.tile_halo(params_) : 0;
  return plan_tiles(need, halo, complexity, limits);
}

void PreparedRun::create(TilePlan plan) {
  tiling_ = std::make_unique<Tiling>(std::move(plan));
  technique_ = descriptor_.create(params_);
  technique_->resize(tiling_->plan().frame_width(), tiling_->plan().frame_height());
}

bool PreparedRun::replan(TilePlan plan) {
  const TilePlan& old = tiling_->plan();
  const bool resized = plan.frame_width() != old.frame_width() || plan.frame_height() != old.frame_height() ||
                       plan.count() != old.count();
  if (resized) technique_->resize(plan.frame_width(), plan.frame_height());
  tiling_ = std::make_unique<Tiling>(std::move(plan));
  return resized;
}

ScreenRect PreparedRun::render_frame(const Frame& frame, bool record, bool scene_rect,
                                     const std::function<void(int)>& after_tile) const {
  return oit::render_frame(*technique_, frame, record, scene_rect, tiling_.get(), after_tile);
}

TechniqueCounters PreparedRun::counters(const Frame& frame, bool scene_rect) const {
  if (!tiling_->plan().tiled()) return technique_->counters();
  std::vector<TechniqueCounters> tiles;
  render_frame(frame, false, scene_rect, [&](int) { tiles.push_back(technique_->counters()); });
  gl_check("the counters frame of " + id());
  return combine_tile_counters(tiles);
}

}  // namespace oit
