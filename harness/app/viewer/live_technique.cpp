#include "harness/app/viewer/live_technique.h"

#include "harness/gl/check.h"

namespace oit {

LiveTechnique::LiveTechnique(const TechniqueRegistry& registry, const DeviceProfile& device, ClockKind clock)
    : registry_(registry), device_(device), clock_kind_(clock) {}

std::string LiveTechnique::configure(const std::string& id, const RawParams& params, const SceneFacts& facts,
                                     SceneShading shading, int width, int height) {
  try {
    auto prepared = std::make_unique<PreparedRun>(registry_, id, params);
    // The frame's content is not known before its first frame; the rules
    // that need it resolve against an empty frame.
    prepared->resolve(device_, facts, FrameContent{width, height, 0, 0});
    if (std::string reason = prepared->unsupported(device_, facts); !reason.empty()) {
      return id + " cannot run here: " + reason;
    }
    // Build everything first so a failure leaves the running one intact.
    // Sized for the whole image as a start (so counters and diagnostics
    // are valid before the first frame); the first frame's tile plan
    // resizes it when the frame must be tiled.
    {
      const SceneShadingScope scope(shading);
      prepared->create(untiled_plan(width, height));
    }
    auto target = std::make_unique<RenderTarget>(width, height);
    gl_check("creating " + id);
    prepared_ = std::move(prepared);
    shading_ = shading;
    planned_scene_ = 0;
    target_ = std::move(target);
    clock_ = std::make_unique<StageClock>(clock_kind_, prepared_->descriptor().stages);
    frames_in_window_ = 0;
    timings_.clear();
    timed_frames_ = 0;
    warmup_left_ = kWarmup;
    id_ = id;
    params_ = params;
    canonical_ = prepared_->params().canonical();
    width_ = width;
    height_ = height;
    return "";
  } catch (const std::exception& e) {
    drain_gl_errors();
    return e.what();
  }
}

void LiveTechnique::render(const SceneGpu& scene, const glm::mat4& view, const glm::mat4& projection,
                           const glm::vec3& background) {
  if (!prepared_) return;
  // The viewer switches scenes under a running technique: one of the other
  // shading gets the technique built again for it (gl/shader_program.h).
  if (scene.shading() != shading_) {
    const SceneShadingScope scope(scene.shading());
    prepared_->create(untiled_plan(width_, height_));
    shading_ = scene.shading();
    planned_scene_ = 0;
    restart_clock();
    timed_frames_ = 0;
    warmup_left_ = kWarmup;
  }
  const SceneShadingScope scope(shading_);  // for the passes a technique builds while rendering
  plan_for(scene, view, projection);
  const Frame frame{scene, view, projection, width_, height_, background, target_->framebuffer.id(), *clock_};
  // Warm-up frames (the first after configure compiles shaders and
  // allocates; the first after a re-plan reallocates) are rendered but not
  // timed, as bench's --warmup frames are not.
  const bool record = warmup_left_ == 0;
  const ScreenRect rect = prepared_->render_frame(frame, record, scene_rect_);
  pixels_outside_ = scene_rect_ ? uint64_t(width_) * uint64_t(height_) - rect.pixels() : 0;
  gl_check("a viewer frame of " + id_);
  if (!record) {
    --warmup_left_;
    return;
  }
  // Until a whole window is there, the table follows every timed frame (a
  // short --frames run shows what it timed); then it changes once per window.
  ++frames_in_window_;
  if (frames_in_window_ == kWindow || timed_frames_ < kWindow) show_window();
  if (frames_in_window_ == kWindow) restart_clock();
}

void LiveTechnique::restart_clock() {
  clock_ = std::make_unique<StageClock>(clock_kind_, prepared_->descriptor().stages);
  frames_in_window_ = 0;
}

void LiveTechnique::plan_for(const SceneGpu& scene, const glm::mat4& view, const glm::mat4& projection) {
  if (planned_scene_ == scene.serial() && planned_view_ == view && planned_projection_ == projection) return;
  if (prepared_->replan(
          prepared_->plan(measure_depth_complexity(scene, view, projection, width_, height_), query_device_limits()))) {
    // Timings of the old plan do not mix with the new one's.
    restart_clock();
    timed_frames_ = 0;
    warmup_left_ = kWarmup;
  }
  planned_scene_ = scene.serial();
  planned_view_ = view;
  planned_projection_ = projection;
}

void LiveTechnique::show_window() {
  timings_.clear();
  // gl clock: results() waits for the window's queries.
  const std::string clock_name = clock_kind_ == ClockKind::gl ? "gl" : "wall";
  for (auto& [name, samples] : clock_->results()) {
    const std::vector<double>& ms = clock_name == "gl" ? samples.gl_ms : samples.wall_ms;
    if (!ms.empty()) timings_.push_back({name, summarize(ms)});
  }
  timed_frames_ = frames_in_window_;
}

Image LiveTechnique::read_image() const { return read_texture_rgba32f(target_->color.id(), width_, height_); }

}  // namespace oit
