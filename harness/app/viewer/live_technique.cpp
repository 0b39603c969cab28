#include "harness/app/viewer/live_technique.h"

#include "harness/gl/check.h"

namespace oit {
namespace {
// The whole image as one tile: a technique's plan until its first frame plans it.
std::unique_ptr<Tiling> one_tile(int width, int height) {
  return std::make_unique<Tiling>(TilePlan{width, height, width, height, 0, {{0, 0, width, height}}, {}});
}
}  // namespace

LiveTechnique::LiveTechnique(const TechniqueRegistry& registry, const DeviceInfo& device, ClockKind clock)
    : registry_(registry), device_(device), clock_kind_(clock) {}

std::string LiveTechnique::configure(const std::string& id, const RawParams& params, const SceneFacts& facts,
                                     SceneShading shading, int width, int height) {
  try {
    const TechniqueDescriptor& descriptor = registry_.get(id);
    const ParamSet values(descriptor.params, params, "technique '" + id + "'");
    if (std::string reason = supports(descriptor, values, device_, facts); !reason.empty()) {
      return id + " cannot run here: " + reason;
    }
    // Build everything first so a failure leaves the running one intact.
    // Sized for the whole image as a start (so counters and diagnostics
    // are valid before the first frame); the first frame's tile plan
    // resizes it when the frame must be tiled.
    std::unique_ptr<Technique> technique = create(descriptor, values, shading, width, height);
    auto target = std::make_unique<RenderTarget>(width, height);
    gl_check("creating " + id);
    technique_ = std::move(technique);
    shading_ = shading;
    descriptor_ = &descriptor;
    values_ = std::make_unique<ParamSet>(values);
    tiling_ = one_tile(width, height);
    planned_scene_ = nullptr;
    target_ = std::move(target);
    clock_ = std::make_unique<StageClock>(clock_kind_, descriptor_->stages);
    frames_in_window_ = 0;
    timings_.clear();
    id_ = id;
    params_ = params;
    canonical_ = values.canonical();
    width_ = width;
    height_ = height;
    return "";
  } catch (const std::exception& e) {
    drain_gl_errors();
    return e.what();
  }
}

std::unique_ptr<Technique> LiveTechnique::create(const TechniqueDescriptor& descriptor, const ParamSet& values,
                                                 SceneShading shading, int width, int height) {
  const SceneShadingScope scope(shading);
  std::unique_ptr<Technique> technique = descriptor.create(values);
  technique->resize(width, height);
  return technique;
}

void LiveTechnique::render(const SceneGpu& scene, const glm::mat4& view, const glm::mat4& projection,
                           const glm::vec3& background) {
  if (!technique_) return;
  // The viewer switches scenes under a running technique: one of the other
  // shading gets the technique built again for it (gl/shader_program.h).
  if (scene.shading() != shading_) {
    technique_ = create(*descriptor_, *values_, scene.shading(), width_, height_);
    shading_ = scene.shading();
    tiling_ = one_tile(width_, height_);
    planned_scene_ = nullptr;
  }
  const SceneShadingScope scope(shading_);  // for the passes a technique builds while rendering
  plan_for(scene, view, projection);
  const Frame frame{scene, view, projection, width_, height_, background, target_->framebuffer.id(), *clock_};
  const ScreenRect rect = render_frame(*technique_, frame, true, scene_rect_, tiling_.get());
  pixels_outside_ = scene_rect_ ? uint64_t(width_) * uint64_t(height_) - rect.pixels() : 0;
  gl_check("a viewer frame of " + id_);
  // The very first frame closes a window at once, so timings show up
  // without waiting (and a short --frames run has them too).
  if (++frames_in_window_ == kWindow || timings_.empty()) finish_window();
}

void LiveTechnique::plan_for(const SceneGpu& scene, const glm::mat4& view, const glm::mat4& projection) {
  if (planned_scene_ == &scene && planned_view_ == view && planned_projection_ == projection) return;
  std::function<StorageNeed(const FrameContent&)> need;
  if (descriptor_->storage_need)
    need = [this](const FrameContent& content) { return descriptor_->storage_need(*values_, content); };
  const int halo = descriptor_->tile_halo ? descriptor_->tile_halo(*values_) : 0;
  TilePlan plan = plan_tiles(need, halo, measure_depth_complexity(scene, view, projection, width_, height_),
                             query_device_limits());
  if (plan.frame_width() != tiling_->plan().frame_width() ||
      plan.frame_height() != tiling_->plan().frame_height() || plan.count() != tiling_->plan().count()) {
    technique_->resize(plan.frame_width(), plan.frame_height());
  }
  tiling_ = std::make_unique<Tiling>(std::move(plan));
  planned_scene_ = &scene;
  planned_view_ = view;
  planned_projection_ = projection;
}

void LiveTechnique::finish_window() {
  timings_.clear();
  // gl clock: results() waits for the window's queries, once per window.
  const std::string clock_name = clock_kind_ == ClockKind::gl ? "gl" : "wall";
  for (auto& [name, samples] : clock_->results()) {
    const std::vector<double>& ms = clock_name == "gl" ? samples.gl_ms : samples.wall_ms;
    if (!ms.empty()) timings_.push_back({name, summarize(ms)});
  }
  clock_ = std::make_unique<StageClock>(clock_kind_, descriptor_->stages);
  frames_in_window_ = 0;
}

Image LiveTechnique::read_image() const { return read_texture_rgba32f(target_->color.id(), width_, height_); }

}  // namespace oit
