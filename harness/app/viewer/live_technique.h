#pragma once
// One technique of the registry rendering frame after frame for the viewer,
// through the harness's own render_frame() and StageClock, so the viewer's
// images and timings are those `oitbench bench` would record.
#include <memory>
#include <string>
#include <vector>

#include "harness/output/image.h"
#include "harness/run/prepared_run.h"
#include "harness/run/statistics.h"

namespace oit {

struct StageTiming {
  std::string stage;
  Summary summary;  // over the last window of frames, milliseconds
};

class LiveTechnique {
 public:
  LiveTechnique(const TechniqueRegistry& registry, const DeviceProfile& device, ClockKind clock);

  // Switches to technique `id` with `params` at `width` x `height`, its
  // programs built for scenes of `shading` (gl/shader_program.h). Returns
  // "" on success, else why not (the schema's validation message, the
  // technique's support check, or the error of its construction); on
  // failure the technique that ran before keeps running unchanged.
  std::string configure(const std::string& id, const RawParams& params, const SceneFacts& facts,
                        SceneShading shading, int width, int height);
  bool ready() const { return prepared_ != nullptr; }

  // Renders one frame into target(); throws what the technique throws. A
  // scene of another shading than the technique's programs were built for
  // gets the technique created again for it first.
  // Whenever the view changes, the storage need is measured again (the
  // harness's counting pass) and the technique re-planned into screen tiles
  // (harness/run/tiling.h) as a bench run would be.
  void render(const SceneGpu& scene, const glm::mat4& view, const glm::mat4& projection, const glm::vec3& background);

  const RenderTarget& target() const { return *target_; }
  Image read_image() const;
  int width() const { return width_; }
  int height() const { return height_; }
  const std::string& id() const { return id_; }
  const RawParams& params() const { return params_; }  // as applied
  const std::string& canonical_params() const { return canonical_; }
  TechniqueCounters counters() const { return prepared_ ? prepared_->technique().counters() : TechniqueCounters{}; }
  // The technique's diagnostic fields of its last frame (none by default).
  std::vector<DiagnosticImage> diagnostic_images() const {
    return prepared_ ? prepared_->technique().diagnostic_images() : std::vector<DiagnosticImage>{};
  }
  // Per-stage timings of the last complete window of kWindow timed frames,
  // or, before the first is complete, of the timed frames so far (empty
  // before the first); timed_frames() says how many frames they cover.
  // Warm-up frames (kWarmup after configure and after every re-plan into
  // a new tile layout: shader compilation, allocation) are never in them.
  const std::vector<StageTiming>& timings() const { return timings_; }
  int timed_frames() const { return timed_frames_; }
  static constexpr int kWindow = 8;
  static constexpr int kWarmup = 1;
  ClockKind clock_kind() const { return clock_kind_; }
  // render_frame's scene rectangle, for every later frame (default on).
  void set_scene_rect(bool on) { scene_rect_ = on; }
  bool scene_rect() const { return scene_rect_; }
  // Pixels of the last frame outside the scene rectangle (0 when it is off):
  // the harness's pixels_outside_scene_rect.
  uint64_t pixels_outside_scene_rect() const { return pixels_outside_; }

 private:
  // kWindow: medians over a few frames are steadier than single frames yet
  // still follow parameter changes within a second or so.
  void show_window();  // timings_ from the clock's frames so far
  void restart_clock();  // a new window: the clock's frames so far are dropped

  const TechniqueRegistry& registry_;
  const DeviceProfile& device_;
  ClockKind clock_kind_;
  // Plans tiles for this view and resizes the technique when the plan changes.
  void plan_for(const SceneGpu& scene, const glm::mat4& view, const glm::mat4& projection);

  // The technique as a bench run resolves it; one tile until the first
  // frame plans it.
  std::unique_ptr<PreparedRun> prepared_;
  SceneShading shading_ = SceneShading::any;  // what the technique's programs were built for
  glm::mat4 planned_view_{0.0f}, planned_projection_{0.0f};
  uint64_t planned_scene_ = 0;  // SceneGpu::serial, 0: none
  std::unique_ptr<RenderTarget> target_;
  std::unique_ptr<StageClock> clock_;
  int frames_in_window_ = 0;  // timed frames in clock_
  int warmup_left_ = 0;       // frames still to render untimed
  int timed_frames_ = 0;      // frames timings_ covers
  std::vector<StageTiming> timings_;
  std::string id_, canonical_;
  RawParams params_;
  int width_ = 0, height_ = 0;
  bool scene_rect_ = true;
  uint64_t pixels_outside_ = 0;
};

}  // namespace oit
