#include "harness/run/runner.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "base/params.h"
#include "harness/run/gpu_clocks.h"
#include "harness/run/memory_failure.h"
#include "harness/run/prepared_run.h"
#include "harness/run/system_load.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"
#include "scenes/model_files.h"
#include "scenes/scene_library.h"

namespace oit {

std::string to_string(RunStatus status) {
  static const Choices<RunStatus> statuses = {
      {RunStatus::ok, "ok"}, {RunStatus::skipped, "skipped"}, {RunStatus::error, "error"}};
  return statuses.name(status);
}

RunSpec run_of(const std::string& technique, const RawParams& params, const std::string& scene,
               const RawParams& scene_params, int width, int height) {
  RunSpec spec;
  spec.technique = technique;
  spec.params = params;
  spec.scene = scene;
  spec.scene_params = scene_params;
  spec.width = width;
  spec.height = height;
  return spec;
}

RunSpec single_frame(const std::string& technique, const RawParams& params, const std::string& scene,
                     const RawParams& scene_params, int width, int height) {
  RunSpec spec = run_of(technique, params, scene, scene_params, width, height);
  spec.warmup = 0;
  spec.frames = 1;
  return spec;
}

const StageResult* RunResult::stage(const std::string& name, const std::string& clock_name) const {
  for (const auto& s : stages)
    if (s.stage == name && s.clock == clock_name) return &s;
  return nullptr;
}

const StageResult* RunResult::total() const { return stage("total", clock == ClockKind::gl ? "gl" : "wall"); }

double RunResult::median_total_ms() const {
  const StageResult* t = total();
  return t ? t->summary.median : 0.0;
}

struct Harness::LoadedScene {
  Scene scene;
  std::unique_ptr<SceneGpu> gpu;
  std::string hash;
  std::map<std::string, DepthComplexity> complexity;  // by size
};

namespace {

std::string key_of(const std::string& scene, const RawParams& params) {
  std::string key = scene;
  for (const auto& [k, v] : params) key += "|" + k + "=" + v;
  return key;
}

}  // namespace

Harness::Harness(GlContext& context, const TechniqueRegistry& registry)
    : context_(context), registry_(registry), reference_cache_(ReferenceCache::from_environment()) {}
Harness::~Harness() = default;

Harness::LoadedScene& Harness::scene(const std::string& spec, const RawParams& params, const std::string& order,
                                     const std::string& camera) {
  const std::string key = key_of(spec, params) + "|order=" + order + "|camera=" + camera;
  auto it = scenes_.find(key);
  if (it == scenes_.end()) {
    auto loaded = std::make_unique<LoadedScene>();
    loaded->scene = load_scene(spec, params);
    reorder_triangles(loaded->scene, order);
    loaded->gpu = std::make_unique<SceneGpu>(loaded->scene);
    // The camera is part of the scene's content hash, so cached references
    // of different viewpoints never mix.
    loaded->scene.camera = resolve_camera(*loaded->gpu, camera);
    loaded->hash = loaded->scene.content_hash();
    it = scenes_.emplace(key, std::move(loaded)).first;
  }
  return *it->second;
}

const Image& Harness::reference_image(const std::string& scene_spec, const RawParams& scene_params, int width,
                                      int height, const glm::vec3& background, const std::string& camera,
                                      std::optional<uint64_t> memory_budget) {
  LoadedScene& loaded = scene(scene_spec, scene_params, "original", camera);
  std::ostringstream key;
  key << loaded.hash << "|" << width << "x" << height << "|" << background.r << "," << background.g << ","
      << background.b;
  auto it = references_.find(key.str());
  if (it != references_.end()) return it->second;
  if (auto cached = reference_cache_.load(key.str(), width, height)) {
    ++references_loaded_;
    return references_.emplace(key.str(), std::move(*cached)).first->second;
  }
  RunResult result;
  result.spec = single_frame(registry_.reference().id, {}, scene_spec, scene_params, width, height);
  RunSpec& spec = result.spec;
  spec.camera = camera;
  spec.clock = result.clock = ClockKind::wall;
  spec.background = background;
  spec.scene_rect = false;  // the reference does not depend on the harness's shortcuts
  spec.memory_budget = memory_budget;
  PreparedRun prepared(registry_, spec.technique, spec.params);
  const DepthComplexity& depth = complexity(loaded, width, height);
  prepared.resolve(device(), {loaded.scene.triangle_count(), loaded.scene.object_count, true},
                   FrameContent{width, height, depth.fragments, depth.max});
  execute(prepared, loaded, result);
  ++references_rendered_;
  reference_cache_.store(key.str(), result.image);
  return references_.emplace(key.str(), std::move(result.image)).first->second;
}

namespace {

void check_run_size(const RunSpec& spec) {
  if (spec.width < 1 || spec.height < 1 || spec.width > 16384 || spec.height > 16384) {
    throw std::invalid_argument("size " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                                " is outside 1x1 .. 16384x16384");
  }
  if (spec.frames < 1 || spec.warmup < 0) throw std::invalid_argument("frames must be >= 1 and warmup >= 0");
}

}  // namespace

namespace {

// The stage rows of a run from its clock: wall and/or gl samples and their
// summaries, and how far the two clocks' totals disagree when both ran.
void record_stages(StageClock& clock, RunResult& result) {
  result.stages.clear();
  for (auto& [name, samples] : clock.results()) {
    if (result.clock != ClockKind::gl)
      result.stages.push_back({name, "wall", summarize(samples.wall_ms), samples.wall_ms});
    if (result.clock != ClockKind::wall)
      result.stages.push_back({name, "gl", summarize(samples.gl_ms), samples.gl_ms});
  }
  if (result.clock == ClockKind::both) {
    const StageResult* wall = result.stage("total", "wall");
    const StageResult* gl = result.stage("total", "gl");
    if (wall && gl && wall->summary.median > 0.0)
      result.clock_disagreement = std::abs(gl->summary.median - wall->summary.median) / wall->summary.median;
  }
}

// The frame-overhead floor with the run, and a warning where the run's
// median total is within 5x of it or a stage's median is below what the
// clock resolves.
void add_overhead_warnings(RunResult& result, double floor_ms) {
  result.frame_overhead_ms = floor_ms;
  const double total = result.median_total_ms();
  char text[200];
  if (floor_ms > 0.0 && total < 5.0 * floor_ms) {
    std::snprintf(text, sizeof text,
                  "the median total %.3g ms is under 5x the empty frame's %.3g ms: mostly fixed per-frame cost, "
                  "use a larger size",
                  total, floor_ms);
    result.warnings.push_back(text);
  }
  // GL timestamps count nanoseconds, the steady clock too; a stage of a few
  // microseconds is below what either resolves through the driver.
  constexpr double kResolutionMs = 0.001;
  for (const StageResult& stage : result.stages)
    if (stage.stage != "total" && stage.summary.median > 0.0 && stage.summary.median < kResolutionMs) {
      std::snprintf(text, sizeof text, "stage %s's median %.2g ms is under the clock's resolution (%g ms)",
                    stage.stage.c_str(), stage.summary.median, kResolutionMs);
      result.warnings.push_back(text);
    }
}

}  // namespace

struct ActiveRun::Parts {
  std::unique_ptr<PreparedRun> prepared;
  const SceneGpu* gpu = nullptr;
  std::unique_ptr<RenderTarget> target;
  std::unique_ptr<StageClock> clock;
  std::unique_ptr<Frame> frame;
  ScreenRect rect;
  std::unique_ptr<OtherProcessLoad> load;
};

ActiveRun::ActiveRun(RunResult result) : result_(std::move(result)), parts_(std::make_unique<Parts>()) {}
ActiveRun::~ActiveRun() = default;

Summary ActiveRun::total_so_far() {
  const std::string total = "total";
  for (auto& [name, samples] : parts_->clock->results())
    if (name == total) return summarize(result_.clock == ClockKind::gl ? samples.gl_ms : samples.wall_ms);
  return {};
}

bool ActiveRun::capped() const {
  const RunSpec& spec = result_.spec;
  if (frames() < spec.frames) return false;  // the least frames come before any cap
  if (spec.precision <= 0.0) return true;
  // Without a cap of its own a run stops at 100000 frames.
  const int most = spec.max_frames > 0 ? spec.max_frames : 100000;
  return frames() >= most || (spec.max_seconds > 0.0 && timed_seconds_ >= spec.max_seconds);
}

bool ActiveRun::wants_more() {
  const RunSpec& spec = result_.spec;
  if (frames() < spec.frames) return true;
  if (capped()) return false;
  return !precision_reached(total_so_far(), spec.precision);
}

RunResult Harness::run(const RunSpec& spec) {
  RunResult result;
  std::unique_ptr<ActiveRun> active = start(spec, result);
  if (!active) return result;
  const RunSpec& asked = active->result().spec;
  while (active->wants_more()) {
    // Judging the precision reads every timer query back (a sync on a GPU):
    // after a batch of an eighth of the frames so far, not after each frame,
    // never past the least frames or the frame cap.
    int batch = std::max(1, active->frames() / 8);
    if (active->frames() < asked.frames) batch = std::min(batch, asked.frames - active->frames());
    if (asked.max_frames > 0) batch = std::max(1, std::min(batch, asked.max_frames - active->frames()));
    if (!render_round(*active, batch, 0)) return std::move(active->result());
  }
  return finish(*active);
}

std::unique_ptr<ActiveRun> Harness::start(const RunSpec& spec, RunResult& result) {
  result = RunResult{};
  result.spec = spec;
  result.clock = spec.clock.value_or(default_clock());
  try {
    // The one resolution of the technique: execute() and the viewer reuse it.
    auto prepared = std::make_unique<PreparedRun>(registry_, spec.technique, spec.params);
    result.technique_params = result.requested_params = prepared->requested().canonical();
    check_run_size(spec);
    // Known before the scene loads, so a skipped row (a model not
    // installed) carries it too and `bench --resume` can find it.
    result.scene_params = canonical_scene_params(spec.scene, spec.scene_params);
    LoadedScene& loaded = scene(spec.scene, spec.scene_params, spec.submission_order, spec.camera);
    result.scene_params = loaded.scene.params;
    const SceneFacts facts{loaded.scene.triangle_count(), loaded.scene.object_count, true};
    // The image first: at sizes the device cannot hold, this is what fails,
    // before the counting pass spends time on them.
    auto target = std::make_unique<RenderTarget>(spec.width, spec.height);
    const DepthComplexity& depth = complexity(loaded, spec.width, spec.height);
    prepared->resolve(device(), facts, FrameContent{spec.width, spec.height, depth.fragments, depth.max});
    result.technique_params = prepared->params().canonical();
    if (std::string reason = prepared->unsupported(device(), facts); !reason.empty()) {
      result.status = RunStatus::skipped;
      result.message = reason;
      return nullptr;
    }
    result.scene_fragments = depth.fragments;
    result.max_depth_complexity = depth.max;
    result.mean_depth_complexity = depth.mean;
    result.psi = depth.psi;
    auto active = std::unique_ptr<ActiveRun>(new ActiveRun(result));
    ActiveRun::Parts& parts = *active->parts_;
    parts.gpu = loaded.gpu.get();
    parts.target = std::move(target);
    {
      // The technique's programs are built for this scene's shading, here and
      // in any pass it builds while rendering (gl/shader_program.h).
      const SceneShadingScope shading(loaded.gpu->shading());
      prepared->create(prepared->plan(depth, query_device_limits(spec.memory_budget)));
    }
    parts.prepared = std::move(prepared);
    parts.clock = std::make_unique<StageClock>(result.clock, parts.prepared->descriptor().stages);
    const float aspect = float(spec.width) / float(spec.height);
    parts.frame = std::make_unique<Frame>(Frame{*loaded.gpu, loaded.scene.camera.view,
                                                loaded.scene.camera.projection(aspect), spec.width, spec.height,
                                                spec.background, parts.target->framebuffer.id(), *parts.clock});
    warm_up(*active);
    if (!gpu_clocks_) gpu_clocks_ = std::make_unique<GpuClocks>();
    active->result_.gpu_start = gpu_clocks_->read();
    parts.load = std::make_unique<OtherProcessLoad>();
    parts.load->start();
    return active;
  } catch (const MissingModel& e) {
    result.status = RunStatus::skipped;  // an optional model not installed here
    result.message = e.what();
  } catch (const std::exception& e) {
    result.status = RunStatus::error;
    result.message = explain_failure(e, spec.width, spec.height);  // a memory failure names the size and remedy
    drain_gl_errors();
    reset_gl_state();
  }
  return nullptr;
}

void Harness::warm_up(ActiveRun& run) {
  ActiveRun::Parts& parts = *run.parts_;
  const RunSpec& spec = run.result_.spec;
  const SceneShadingScope shading(parts.gpu->shading());
  const double cap_ms = std::max(4.0 * spec.warmup_ms, 1000.0);
  std::vector<double> frame_ms;
  double elapsed_ms = 0.0;
  auto stable = [&] {
    if (frame_ms.size() < 6) return false;
    std::vector<double> last(frame_ms.end() - 3, frame_ms.end()), before(frame_ms.end() - 6, frame_ms.end() - 3);
    const double a = summarize(last).median, b = summarize(before).median;
    return std::abs(a - b) <= 0.10 * a;
  };
  while (int(frame_ms.size()) < spec.warmup ||
         ((elapsed_ms < spec.warmup_ms || (spec.warmup_ms > 0.0 && !stable())) && elapsed_ms < cap_ms)) {
    if (spec.warmup == 0 && spec.warmup_ms <= 0.0) break;
    const auto begin = std::chrono::steady_clock::now();
    parts.rect = parts.prepared->render_frame(*parts.frame, false, spec.scene_rect);
    glFinish();
    gl_check("warm-up frame " + std::to_string(frame_ms.size()) + " of " + spec.technique);
    frame_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count());
    elapsed_ms += frame_ms.back();
  }
  run.result_.warmup_frames = int(frame_ms.size());
  if (spec.warmup_ms > 0.0 && frame_ms.size() >= 6 && !stable())
    run.result_.warnings.push_back("warm-up ended at its cap (" + std::to_string(int(cap_ms)) +
                                   " ms) before the frame time was stable");
}

bool Harness::render_round(ActiveRun& run, int frames, int round) {
  ActiveRun::Parts& parts = *run.parts_;
  RunResult& result = run.result_;
  try {
    const SceneShadingScope shading(parts.gpu->shading());
    for (int i = 0; i < frames; ++i) {
      const auto begin = std::chrono::steady_clock::now();
      parts.rect = parts.prepared->render_frame(*parts.frame, true, result.spec.scene_rect);
      gl_check("frame " + std::to_string(run.frames()) + " of " + result.spec.technique);
      run.timed_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
      result.frame_rounds.push_back(round);
    }
    // Read while the clock still reflects the load: by finish() the GPU may
    // have idled (a data-centre part drops to its idle clock within
    // moments), which would flag every run. Each round overwrites it, so the
    // last timed frame's is kept.
    if (frames > 0 && gpu_clocks_) result.gpu_end = gpu_clocks_->read();
    return true;
  } catch (const std::exception& e) {
    result.status = RunStatus::error;
    result.message = explain_failure(e, result.spec.width, result.spec.height);
    drain_gl_errors();
    reset_gl_state();
    return false;
  }
}

RunResult Harness::finish(ActiveRun& run) {
  ActiveRun::Parts& parts = *run.parts_;
  RunResult& result = run.result_;
  const RunSpec& spec = result.spec;
  try {
    result.other_process_load = parts.load->stop();
    result.noisy = result.other_process_load > kNoisyLoadThreshold;
    if (result.gpu_start && result.gpu_end)
      if (const std::string moved = clock_moved_warning(*result.gpu_start, *result.gpu_end); !moved.empty()) {
        result.noisy = true;
        result.warnings.push_back(moved);
      }
    {
      const SceneShadingScope shading(parts.gpu->shading());
      result.tiles = parts.prepared->tiling().plan().count();
      // Counters describe the technique's last frame.
      result.counters = parts.prepared->counters(*parts.frame, spec.scene_rect);
    }
    // The harness's own adaptive path: pixels every full-screen pass skipped.
    if (spec.scene_rect) {
      result.counters.work_saved.push_back(
          {kPixelsOutsideSceneRect, double(uint64_t(spec.width) * uint64_t(spec.height) - parts.rect.pixels())});
    }
    result.image = read_texture_rgba32f(parts.target->color.id(), spec.width, spec.height);
    gl_check("reading back the image of " + spec.technique);
    record_stages(*parts.clock, result);
    result.rounds = result.frame_rounds.empty() ? 0 : result.frame_rounds.back() + 1;
    if (const StageResult* total = result.total()) {
      result.precision_reached = spec.precision > 0.0 && precision_reached(total->summary, spec.precision);
      for (std::string& warning : frame_warnings(total->samples_ms)) result.warnings.push_back(std::move(warning));
      add_overhead_warnings(result, frame_overhead_ms(result.clock == ClockKind::gl ? ClockKind::gl : ClockKind::wall));
    }
    // The scene's size goes with every row so plots against triangles or
    // vertices (carnecky2013 Fig. 15, pastyrik2016 Fig. 9) need only the CSV.
    result.counters.extra.push_back({"scene_triangles", double(parts.gpu->scene().triangle_count()), Combine::max});
    result.counters.extra.push_back({"scene_vertices", double(parts.gpu->scene().vertices.size()), Combine::max});
    parts = ActiveRun::Parts{};  // the technique's storage goes before the reference's
    compare_with_reference(spec, result);
  } catch (const std::exception& e) {
    result.status = RunStatus::error;
    result.message = explain_failure(e, spec.width, spec.height);
    drain_gl_errors();
    reset_gl_state();
  }
  return std::move(result);
}

double Harness::frame_overhead_ms(ClockKind clock) {
  if (auto found = frame_overhead_ms_.find(clock); found != frame_overhead_ms_.end()) return found->second;
  // A target and a draw of one triangle with rasterizer discard: the frame's
  // fixed cost (clear, state, the clock's own brackets), no fragment work.
  RenderTarget target(64, 64);
  const Program empty = build_fullscreen_program("shaders/empty_frame.frag");
  StageClock stage_clock(clock);
  const VertexArray vertex_array = make_vertex_array();
  for (int i = 0; i < 25; ++i) {
    begin_target(target.framebuffer.id(), glm::vec3(0.0f), nullptr);
    stage_clock.begin_frame(i >= 5);
    {
      auto total = stage_clock.stage("total");
      glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer.id());
      glEnable(GL_RASTERIZER_DISCARD);
      glUseProgram(empty.id());
      glBindVertexArray(vertex_array.id());
      glDrawArrays(GL_TRIANGLES, 0, 3);
      glDisable(GL_RASTERIZER_DISCARD);
    }
    stage_clock.end_frame();
  }
  reset_gl_state();
  gl_check("the empty frames of the frame-overhead floor");
  double median = 0.0;
  for (auto& [name, samples] : stage_clock.results())
    if (name == "total") median = summarize(clock == ClockKind::gl ? samples.gl_ms : samples.wall_ms).median;
  return frame_overhead_ms_[clock] = median;
}

void Harness::compare_with_reference(const RunSpec& spec, RunResult& result) {
  try {
    result.error = compare_images(result.image, reference_image(spec.scene, spec.scene_params, spec.width, spec.height,
                                                                spec.background, spec.camera, spec.memory_budget));
  } catch (const std::exception& e) {
    // The run's timings stand; only its error is unknown.
    result.message = std::string("no reference image, error columns empty: ") + e.what();
    drain_gl_errors();
    reset_gl_state();
  }
}

const DepthComplexity& Harness::complexity(LoadedScene& loaded, int width, int height) {
  const std::string size_key = std::to_string(width) + "x" + std::to_string(height);
  auto found = loaded.complexity.find(size_key);
  if (found == loaded.complexity.end()) {
    const glm::mat4 projection = loaded.scene.camera.projection(float(width) / float(height));
    found = loaded.complexity
                .emplace(size_key,
                         measure_depth_complexity(*loaded.gpu, loaded.scene.camera.view, projection, width, height))
                .first;
  }
  return found->second;
}

TilePlan Harness::tile_plan(const RunSpec& spec) {
  PreparedRun prepared(registry_, spec.technique, spec.params);
  LoadedScene& loaded = scene(spec.scene, spec.scene_params, spec.submission_order, spec.camera);
  const DepthComplexity& depth = complexity(loaded, spec.width, spec.height);
  prepared.resolve(device(), {loaded.scene.triangle_count(), loaded.scene.object_count, true},
                   FrameContent{spec.width, spec.height, depth.fragments, depth.max});
  return prepared.plan(depth, query_device_limits(spec.memory_budget));
}


void Harness::execute(PreparedRun& prepared, LoadedScene& loaded, RunResult& result) {
  const RunSpec& spec = result.spec;
  const SceneShadingScope shading(loaded.gpu->shading());
  prepared.create(
      prepared.plan(complexity(loaded, spec.width, spec.height), query_device_limits(spec.memory_budget)));
  RenderTarget target(spec.width, spec.height);
  StageClock clock(result.clock, prepared.descriptor().stages);
  const float aspect = float(spec.width) / float(spec.height);
  const Frame frame{*loaded.gpu,  loaded.scene.camera.view,   loaded.scene.camera.projection(aspect),
                    spec.width,   spec.height,                spec.background,
                    target.framebuffer.id(), clock};
  for (int i = 0; i < spec.warmup + spec.frames; ++i) {
    prepared.render_frame(frame, i >= spec.warmup, spec.scene_rect);
    gl_check("frame " + std::to_string(i) + " of " + spec.technique);
  }
  result.tiles = prepared.tiling().plan().count();
  result.image = read_texture_rgba32f(target.color.id(), spec.width, spec.height);
  gl_check("reading back the image of " + spec.technique);
  record_stages(clock, result);
}

}  // namespace oit
