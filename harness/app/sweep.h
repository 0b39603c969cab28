#pragma once
// Expansion of command-line sweep options into individual runs, shared by
// the `oitbench` CLI and the Google Benchmark binary.
#include <string>
#include <vector>

#include "harness/run/results_csv.h"
#include "harness/run/runner.h"

namespace oit {

// The image size of every command that renders (render, bench, stats,
// adaptive, oitbench_gbench) unless --size says otherwise: `auto`, the device
// profile's default_size (256x256 on software GL, 1920x1080 on a GPU, where
// the work must dominate the frame's fixed cost); pareto alone defaults
// smaller (main.cpp says why).
inline const std::string kDefaultSize = "auto";

struct SweepOptions {
  std::vector<std::string> techniques{"all"};
  std::vector<std::string> scenes{"quads"};
  // "key=v1,v2" or "technique.key=v1,v2"; a key applies to the selected
  // techniques that have it (and must exist in at least one of them), a
  // scoped one to its technique only (which must be selected), where it
  // overrides the unscoped key; a key given twice for one scope is an error.
  std::vector<std::string> technique_sets;
  // "key=v1,v2" or "scene.key=v1,v2", as technique_sets: a key applies to
  // the selected scenes that have it (and must exist in at least one).
  std::vector<std::string> scene_sets;
  std::vector<std::string> sizes{kDefaultSize};
  // Camera specs (scenes/cameras.h); a random:N:SEED set becomes N runs.
  std::vector<std::string> cameras{"default"};
  // The harness's scene rectangle (RunSpec::scene_rect): "on", "off" or both.
  std::vector<std::string> scene_rects{"on"};
  // Each run's frames: precision-driven (at least `frames`, more until
  // `precision` or a cap), warm-up time the device profile's
  // (warmup_ms < 0).
  Repetition repetition{.warmup = 1, .warmup_ms = -1.0, .frames = 6, .precision = 0.05, .max_frames = 200,
                        .max_seconds = 2.0};
  // --frames N: exactly N timed frames instead, no precision target, no cap (0: none).
  int exact_frames = 0;
  // What `auto` in sizes and warmup_ms become (expand_sweep): the device
  // profile's, once the context is open; before that, for validation only,
  // the software defaults.
  std::string auto_size = "256x256";
  double auto_warmup_ms = 0.0;
  std::string clock = "auto";
  std::string background = "0,0,0";
  // RunSpec::memory_budget as text ("512M", "2G"); empty: the device's default.
  std::string memory_budget;
};

// The techniques `ids` name ("all": every registered one), each once, in
// the order given; throws naming an unknown id.
std::vector<const TechniqueDescriptor*> selected_techniques(const std::vector<std::string>& ids,
                                                            const TechniqueRegistry& registry);

// Every combination of the options, in the sweep's order (scene, scene
// parameters, camera, size, technique, parameters, scene rectangle). Each
// combination's technique and scene parameters are checked first
// (validate_sweep): a bad value anywhere throws before anything runs.
std::vector<RunSpec> expand_sweep(const SweepOptions& options, const TechniqueRegistry& registry);

// Throws std::invalid_argument naming the first run whose technique, scene,
// parameter or value is invalid ("bench --set k=abc" fails here, not as an
// error row hours into the sweep). A scene file that does not exist is not
// checked: it stays an error row of its runs.
void validate_sweep(const std::vector<RunSpec>& runs, const TechniqueRegistry& registry);

// For the commands that run each technique once, one value per key
// (render, check-order, view): the parameters `--set key=value` and
// `--set technique.key=value` give each of `techniques`, in their order. The
// texts are checked as a sweep's are: a scope that is no technique or not a
// selected one, a key no selected technique has (with the closest one
// suggested) and a key given twice are errors naming the text. A key a
// technique's own scope sets overrides the unscoped one for it.
std::vector<RawParams> one_value_technique_params(const std::vector<std::string>& sets,
                                                  const std::vector<const TechniqueDescriptor*>& techniques,
                                                  const TechniqueRegistry& registry);
// The same for `--scene-set` and the one scene of render, check-order,
// stats and view (`scene.key=value` must name that scene); an unknown scene
// is named first.
RawParams one_value_scene_params(const std::vector<std::string>& scene_sets, const std::string& scene);

// bench/pareto --baseline: throws when it is no technique id (suggesting the
// closest, or the id of "id:key=value") or not among `techniques` (the -t
// list, "all" included); otherwise the summary would quietly divide by
// each block's fastest run instead.
void validate_baseline(const std::string& baseline, const std::vector<std::string>& techniques,
                       const TechniqueRegistry& registry);

// A warning for stderr when `clock` ("auto", "gl", "wall", "both") asks for
// GL timer queries on a software device, whose per-pass times they get
// wrong (docs/REFERENCE.md, Timing); "" otherwise.
std::string clock_warning(const std::string& clock, const DeviceProfile& device);

// The key the run's CSV rows will carry (parameters canonical, defaults
// filled in, as the harness writes them), for `bench --resume`; nullopt when
// a parameter is invalid (that run is an error row, never finished).
std::optional<RunKey> resume_key(const RunSpec& spec, const TechniqueRegistry& registry);

// The warm-up and timed-frame fields of `spec` from the options.
void apply_repetition(const SweepOptions& options, RunSpec& spec);

// `text`, or for "auto" the device's default size.
std::string size_for(const std::string& text, const DeviceProfile& device);
// "256x256" or "256X256", 1 .. 16384 each; throws naming the text (a lone
// "256" with "did you mean 256x256?"). "auto" parses as 256x256 (use
// size_for once the device is known).
void parse_size(const std::string& text, int& width, int& height);
// "r,g,b", linear: finite and >= 0 each; throws naming the text.
glm::vec3 parse_background(const std::string& text);
// "on" -> true, "off" -> false; throws naming the text otherwise.
bool parse_on_off(const std::string& option, const std::string& text);
// How one place writes a run's name: what goes between the fields, between
// a parameter's key and its value, before the scene and a camera that is not
// the default, and for a scene rectangle that is off.
struct RunNaming {
  const char* separator;
  const char* assign;
  const char* scene;
  const char* camera;
  const char* scene_rect_off;
};
// The fields that tell the runs of a sweep apart, in one order: technique
// and its parameters as given, scene and its parameters, size, camera,
// scene rectangle; e.g. "kbuffer k=16 on quads layers=8 64x64" with
// {" ", "=", " on ", " camera ", " scene_rect off"}.
std::string run_name(const RunSpec& spec, const RunNaming& naming);

// Label for file names, distinct for every run a sweep expands to:
// technique and its parameters as given, scene (a file's name) and its
// parameters, size, then "_camera-..." when the camera is not the default
// and "_scene-rect-off"; only [A-Za-z0-9_.-]:
// "kbuffer_k-16_tail-drop_quads_objects-3_256x256_camera-random-4-7-2".
std::string run_label(const RunResult& result);

}  // namespace oit
