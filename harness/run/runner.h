#pragma once
// Runs one technique on one scene/camera/size: warm-up, timed frames, stage
// statistics, counters, image and its error against the cached exact
// reference. A run that cannot happen is `skipped` with the reason; a run
// that fails is `error` with the message. Nothing here knows any technique.
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "harness/run/complexity.h"
#include "harness/run/gpu_clocks.h"
#include "harness/output/error_metrics.h"
#include "harness/output/image.h"
#include "harness/run/reference_cache.h"
#include "harness/toolkit/scene_rect.h"
#include "harness/run/statistics.h"
#include "harness/toolkit/technique.h"
#include "harness/run/tiling.h"

namespace oit {

// How many frames a run renders: its warm-up, and its timed frames and when
// they stop. A run's (RunSpec) and the defaults a sweep gives each of its
// runs (SweepOptions, harness/app/sweep.h).
struct Repetition {
  // Warm-up: at least `warmup` frames and `warmup_ms` of them, and on until
  // the frame time is stable (the median of the last three frames within 10%
  // of the three before) or a cap of max(4 x warmup_ms, 1 s) is reached. A
  // sweep's negative warmup_ms is the device profile's default_warmup_ms
  // (expand_sweep puts it in each run).
  int warmup = 2;
  double warmup_ms = 0.0;
  // Timed frames: at least `frames`; with `precision` > 0, more until the 95%
  // interval of the median total lies within +-precision of it (relative),
  // or `max_frames` or `max_seconds` of timed frames is reached (0: no cap
  // of that kind; a run that stops there has precision_reached false).
  int frames = 10;
  double precision = 0.0;
  int max_frames = 0;
  double max_seconds = 0.0;
};

// What one run renders, and how often (its Repetition).
struct RunSpec : Repetition {
  std::string technique;
  RawParams params;
  std::string scene = "quads";
  RawParams scene_params;
  // Triangle submission order: "original", "reversed", "shuffled:SEED" or
  // "objects_shuffled:SEED" (see reorder_triangles).
  // The reference is always rendered in the original order.
  std::string submission_order = "original";
  // One viewpoint (scenes/cameras.h): "default" (the scene's camera),
  // "random:N:SEED@I" or "max_list[:N:SEED]". Reference and depth
  // complexity use the same camera.
  std::string camera = "default";
  int width = 256;
  int height = 256;
  std::optional<ClockKind> clock;  // default: the device profile's trusted clock
  glm::vec3 background{0.0f};
  // Scissor the technique's frame to the scene's projected rectangle
  // (render_frame); off renders every pass over the full image. The image
  // is the same either way; the CSV's scene_rect column records it.
  bool scene_rect = true;
  // Bytes all of a technique's storage may take before the frame is tiled
  // (harness/run/tiling.h); default: query_device_limits()'s budget. Applies to
  // the run and to its reference.
  std::optional<uint64_t> memory_budget;
};

// `technique` with `params` on `scene` with `scene_params`, width x height:
// what a run renders; the other fields at their defaults.
RunSpec run_of(const std::string& technique, const RawParams& params, const std::string& scene,
               const RawParams& scene_params, int width, int height);
// run_of() for one frame without warm-up: the runs that take an image
// rather than times (the reference, stress, the tests).
RunSpec single_frame(const std::string& technique, const RawParams& params, const std::string& scene,
                     const RawParams& scene_params, int width, int height);

// The work_saved entry of a run with RunSpec::scene_rect: pixels outside the
// scene's rectangle, which every scissored pass skipped.
inline constexpr const char* kPixelsOutsideSceneRect = "pixels_outside_scene_rect";

enum class RunStatus { ok, skipped, error };
std::string to_string(RunStatus status);

struct StageResult {
  std::string stage;
  std::string clock;  // "gl" or "wall"
  Summary summary;
  std::vector<double> samples_ms;
};

struct RunResult {
  RunSpec spec;
  // Canonical "k=16 tail=drop": as run, every auto resolved (params), and as
  // asked for, defaults filled in (requested_params).
  std::string technique_params;
  std::string requested_params;
  std::string scene_params;      // canonical
  ClockKind clock = ClockKind::wall;
  RunStatus status = RunStatus::ok;
  std::string message;
  std::vector<StageResult> stages;
  TechniqueCounters counters;
  std::optional<ImageError> error;
  uint64_t scene_fragments = 0;
  uint32_t max_depth_complexity = 0;
  double mean_depth_complexity = 0.0;
  double psi = 0.0;  // complexity coverage (DepthComplexity::psi)
  // Screen tiles each frame was rendered in (1: untiled); see tiling.h.
  int tiles = 1;
  double other_process_load = -1.0;  // share of all cores; -1 unknown
  bool noisy = false;
  int warmup_frames = 0;        // the warm-up frames run
  int rounds = 1;               // rounds its timed frames ran in (interleaved with others)
  bool precision_reached = false;
  // The median total over the baseline's, paired by round (bench --rounds).
  std::string baseline;
  std::optional<RatioEstimate> ratio;
  // Why its time is suspect: drift, outlying frames, a clock that moved, a
  // median near the frame-overhead floor... (statistics.h, runner.cpp).
  std::vector<std::string> warnings;
  // The median time of an empty frame on the run's clock (Harness::frame_overhead_ms).
  std::optional<double> frame_overhead_ms;
  std::optional<GpuClockReading> gpu_start, gpu_end;
  // Per timed frame, the round it ran in.
  std::vector<int> frame_rounds;
  // |gl - wall| / wall of the median total, when both clocks ran.
  std::optional<double> clock_disagreement;
  Image image;

  const StageResult* stage(const std::string& name, const std::string& clock) const;
  // The `total` stage of the run's own clock (gl, or wall for wall and
  // both); nullptr when the run did not time anything.
  const StageResult* total() const;
  // Its median in ms, 0 when there is none.
  double median_total_ms() const;
};

class PreparedRun;

// A run in progress (Harness::start): its technique resolved, created and
// warmed up, its timed frames added by Harness::render_round, alone or in
// rounds interleaved with other runs, and its figures read by
// Harness::finish.
class ActiveRun {
 public:
  ~ActiveRun();
  RunResult& result() { return result_; }
  // Timed frames so far, and the seconds they took on the wall clock.
  int frames() const { return int(result_.frame_rounds.size()); }
  double timed_seconds() const { return timed_seconds_; }
  // The median total of the frames so far and its interval.
  Summary total_so_far();
  // Whether it needs more frames: fewer than spec.frames, or a precision
  // not reached and no cap hit.
  bool wants_more();
  // Whether it may take no more frames: at least spec.frames, and its
  // fixed count (no precision target), max_frames or max_seconds reached.
  bool capped() const;

 private:
  friend class Harness;
  struct Parts;
  explicit ActiveRun(RunResult result);
  RunResult result_;
  std::unique_ptr<Parts> parts_;
  double timed_seconds_ = 0.0;
};

class Harness {
 public:
  Harness(GlContext& context, const TechniqueRegistry& registry);
  ~Harness();

  const DeviceProfile& device() const { return context_.device(); }
  const TechniqueRegistry& registry() const { return registry_; }
  ClockKind default_clock() const { return parse_clock_kind(device().trusted_clock); }

  // start, render_round until wants_more() says enough, finish.
  RunResult run(const RunSpec& spec);
  // Resolves the technique for the device and scene, checks it can run,
  // creates it and warms it up. nullptr when the run cannot happen or fails:
  // then `result` is its skipped or error row.
  std::unique_ptr<ActiveRun> start(const RunSpec& spec, RunResult& result);
  // `frames` timed frames of round `round`; false when they failed (the
  // result is then an error row and the run is over).
  bool render_round(ActiveRun& run, int frames, int round);
  // Counters, image, stage statistics, warnings and the error against the
  // reference; the run's result.
  RunResult finish(ActiveRun& run);
  // The median time of an empty frame (a clear and a draw that produces no
  // fragment) on `clock`, measured once per harness: the floor under every
  // run's total.
  double frame_overhead_ms(ClockKind clock);
  // The exact image of a scene/size/background, computed once and cached in
  // memory and on disk (ReferenceCache::from_environment()).
  // Rendered in tiles when its storage exceeds the device's limits or
  // `memory_budget` (bytes; default: the device's budget).
  const Image& reference_image(const std::string& scene, const RawParams& scene_params, int width, int height,
                               const glm::vec3& background, const std::string& camera = "default",
                               std::optional<uint64_t> memory_budget = std::nullopt);
  // The tile plan of a technique for a scene at a size: one tile when its
  // storage fits the device's limits and the budget.
  TilePlan tile_plan(const RunSpec& spec);
  void set_reference_cache(ReferenceCache cache) { reference_cache_ = std::move(cache); }
  // How this harness got its references so far: rendered, or read from disk.
  int references_rendered() const { return references_rendered_; }
  int references_loaded() const { return references_loaded_; }

 private:
  struct LoadedScene;
  LoadedScene& scene(const std::string& spec, const RawParams& params, const std::string& order = "original",
                     const std::string& camera = "default");
  // Renders result.spec's frames, warm-up included, with the technique
  // `prepared` resolved, on the clock result.clock, into a target of its
  // own: the reference's one frame.
  void execute(PreparedRun& prepared, LoadedScene& loaded, RunResult& result);
  void warm_up(ActiveRun& run);
  const DepthComplexity& complexity(LoadedScene& loaded, int width, int height);
  // Sets result.error, or says in result.message why there is no reference.
  void compare_with_reference(const RunSpec& spec, RunResult& result);

  GlContext& context_;
  const TechniqueRegistry& registry_;
  std::map<std::string, std::unique_ptr<LoadedScene>> scenes_;
  std::map<std::string, Image> references_;
  ReferenceCache reference_cache_;
  int references_rendered_ = 0, references_loaded_ = 0;
  std::map<ClockKind, double> frame_overhead_ms_;
  std::unique_ptr<GpuClocks> gpu_clocks_;
};

}  // namespace oit
