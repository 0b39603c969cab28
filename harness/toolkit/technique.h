#pragma once
// The interface every OIT technique implements, and the registry that lists
// them. A technique lives in algorithms/<id>/ and registers itself through
// the build-generated registry; nothing here knows any technique.
#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "base/params.h"
#include "harness/toolkit/scene_gpu.h"
#include "harness/toolkit/stage_clock.h"
#include "harness/gl/context.h"

namespace oit {

// How one figure of TechniqueCounters combines over the screen tiles of a
// frame (harness/run/tiling.h): counts add up; sizes take the largest tile's;
// ratios (precision, mean errors) average weighted by each tile's stored
// fragments.
enum class Combine { sum, max, mean };

struct Figure {
  std::string name;  // snake_case
  double value = 0.0;
  Combine combine = Combine::sum;
};

// The value of the figure called `name`, if there is one.
std::optional<double> find_figure(const std::vector<Figure>& figures, const std::string& name);

struct TechniqueCounters {
  uint64_t bytes_allocated = 0;    // GPU memory the technique owns now
  uint64_t fragments_stored = 0;   // fragments kept in the last frame
  uint64_t fragments_dropped = 0;  // fragments lost (truncation) in the last frame
  uint64_t passes = 0;             // geometry passes in the last frame
  uint64_t overflow_retries = 0;   // re-renders after a buffer overflow, since construction
  // Technique-specific figures (e.g. neighbour links per direction,
  // neighbour precision), written to the CSV's `extra` column as
  // "name=value name=value". Names are snake_case.
  std::vector<Figure> extra;
  // Work the technique's adaptive paths avoided in the last frame against
  // its non-adaptive path on the same scene (e.g. passes_avoided,
  // fragments_not_sorted, bytes_not_allocated), written to the CSV's
  // `work_saved` column like `extra`. Empty when nothing adapts.
  std::vector<Figure> work_saved;
};

// A per-pixel scalar field a technique can show about its last frame (e.g.
// neighbour links or curvature of each pixel's front fragment), for the
// viewer's `--display diagnostic`. Technique-independent: the harness only
// draws it as a heatmap over [low, high].
struct DiagnosticImage {
  std::string name;         // snake_case, unique per technique
  std::string description;  // one line: what a value means
  int width = 0, height = 0;
  std::vector<float> values;  // one per pixel, rows bottom-up like Image; NaN = no value (drawn black)
  float low = 0.0f, high = 1.0f;  // the field's natural range (the heatmap's blue and red ends)
};

struct TechniqueNeeds {
  bool fp64 = false;              // double precision in shaders
  bool int64 = false;             // 64-bit integers in shaders (GL_ARB_gpu_shader_int64)
  bool indexed_geometry = false;  // shared vertex indices (triangle adjacency)
  bool multiple_objects = false;  // more than one object id
};

// What a technique may ask of the scene it is about to run on.
struct SceneFacts {
  size_t triangles = 0;
  uint32_t objects = 0;
  bool indexed = true;
};

// What a technique promises about its image against the exact reference
// (docs/ARCHITECTURE.md, "The plugin contract"):
// - exact: within exact_tolerance of the reference on every scene whose
//   depth complexity its default caps cover (60 fragments per pixel or
//   more), dropping nothing there; beyond a cap it counts, in
//   fragments_dropped, every fragment it could not keep.
// - exact_while_storage_covers: a fixed per-pixel storage (k slots) that a
//   scene may outgrow; every fragment the storage could not hold is counted
//   in fragments_dropped, and a run that counted none is exact.
// - approximate: no promise about the reference; a finite image in
//   [0, output_max].
enum class Exactness { exact, exact_while_storage_covers, approximate };

// "exact", "exact while storage covers", "approximate": what `list`, the
// README's technique table and the viewer call the class.
const char* to_string(Exactness exactness);
// Whether a run of a technique of this class that dropped
// `fragments_dropped` fragments must match the reference within its
// exact_tolerance: exact and exact-while-storage-covers runs that dropped
// nothing; a run that counted its truncation is judged on finiteness only.
bool held_to_reference(Exactness exactness, uint64_t fragments_dropped);

struct FrameContent;

// What a resolution rule (TechniqueDescriptor::resolve) decides from: the
// device's profile, the scene, what the frame holds (the harness's counting
// pass) and the parameters the user set (the rest hold their defaults).
struct ResolveInput {
  const DeviceProfile& device;
  SceneFacts scene;
  const FrameContent& content;
  const RawParams& given;
};

// One adaptive feature of a technique ("skip what the scene does not
// need"), as the parameter settings that turn it on and off. `oitbench
// adaptive` runs both on the same scenes and reports time and memory ratios
// and the image difference between them.
struct AdaptiveSwitch {
  std::string feature;      // snake_case, e.g. "early_exit"
  std::string description;  // one line: what the feature skips
  RawParams on, off;
};

// Everything a technique needs to render one frame.
struct Frame {
  const SceneGpu& scene;
  glm::mat4 view;
  glm::mat4 projection;
  int width;
  int height;
  glm::vec3 background;
  GLuint target_framebuffer;  // RGBA32F; compose passes write here
  StageClock& clock;
  // A tiled frame (harness/run/tiling.h) renders the technique once per screen
  // tile: width x height and projection are then the tile's, and
  // `tile_index` tells the tiles apart (e.g. for per-tile pool history).
  int tile_index = 0;
  int tile_count = 1;
  // Where this frame's pixel (0, 0) lies in the whole image (a tile's
  // offset): shaders/shading.glsl's oit_image_pixel().
  int origin_x = 0, origin_y = 0;

  // Sets whichever shared uniforms `program` uses: the camera of
  // shaders/geometry.vert, u_lit and u_pixel_origin of shading.glsl,
  // u_background of compose.glsl. Throws std::logic_error when `program`
  // was built for the other scene shading than this scene's
  // (gl/shader_program.h, SceneShading).
  void set_shared_uniforms(GLuint program) const;
  // Binds the target framebuffer with a full viewport.
  void bind_target() const;
  // View depths of the projection's near and far planes (perspective or
  // orthographic).
  glm::vec2 near_far() const;
};

class Technique {
 public:
  virtual ~Technique() = default;
  // Resolution-dependent resources are (re)built here, not in the constructor.
  virtual void resize(int width, int height) = 0;
  virtual void render(const Frame& frame) = 0;
  virtual TechniqueCounters counters() const = 0;
  // Diagnostic fields of the last rendered frame, read back after it
  // (outside the timed frames, like counters()). Default: none.
  virtual std::vector<DiagnosticImage> diagnostic_images() const { return {}; }
};

// What a frame will hold, known before it renders from the harness's
// counting pass (harness/run/complexity.h): its size and fragments.
struct FrameContent {
  int width = 0, height = 0;
  uint64_t fragments = 0;
  uint32_t longest_list = 0;
  uint64_t pixels() const { return uint64_t(width) * uint64_t(height); }
};

// GPU storage a technique needs for one frame: its largest single buffer
// (bounded by the device's largest storage block) and everything together
// (bounded by the memory budget). The harness tiles the screen until both
// fit (harness/run/tiling.h).
struct StorageNeed {
  uint64_t largest_buffer = 0;
  uint64_t total = 0;
};

// The parameter the registry adds to a technique with a paper preset.
inline constexpr const char* kPresetParameter = "preset";

// What a technique is, for the registry. A technique registers one, written
// as a single designated initializer in its register_technique_<id> (fields
// in this order; leave out what keeps its default):
//   registry.add({.id = "my_oit", .display_name = "...", .paper = "...",
//                 .params = {...}, .stages = {...}, .create = make_technique<MyOit>});
struct TechniqueDescriptor {
  std::string id;            // snake_case, the CSV key
  std::string display_name;
  std::string paper;         // citation shown by `list` and the README
  ParamSchema params;
  std::vector<std::string> stages;  // the stage names it emits, in order: any distinct snake_case words but "total"
  TechniqueNeeds needs;
  Exactness exactness = Exactness::approximate;
  // For exact techniques: the largest difference from the reference that
  // still counts as exact (1e-5 for float compositing; a technique storing
  // colour packed states the quantisation bound of its storage here).
  double exact_tolerance = 1e-5;
  // The largest channel value a correct output can hold, which `stress`
  // holds it to (besides finiteness, and >= 0): 1 for compositing, which
  // blends colours in [0, 1]; infinity for an approximation whose output is
  // legitimately unbounded (a weighted sum over many layers exceeds 1).
  double output_max = 1.0;
  // Knobs for run-time-versus-error sweeps (`oitbench pareto`): parameter
  // name and the values to try, cheapest first. Quality knobs trade time
  // for error; an exact technique's speed options (its error is the same
  // at every value) are swept too, so the plot shows which path is fastest.
  std::vector<std::pair<std::string, std::vector<std::string>>> quality_sweep;
  std::vector<AdaptiveSwitch> adaptive_switches;
  bool is_reference = false;  // the exact technique the harness compares against
  // Optional extra check of the resolved parameters; returns "" when the run
  // can happen, else the reason.
  std::function<std::string(const ParamSet&, const SceneFacts&, const DeviceProfile&)> extra_support_check;
  // The resolution rule: turns every `auto` and every device- or
  // scene-dependent default into the value that will run, before the
  // technique is created, and returns those assignments ({{"storage",
  // "linked"}}); the harness applies them over what the user gave and
  // validates the result. The technique is then built from concrete values
  // and never asks what the device is. Empty: nothing to resolve.
  std::function<RawParams(const ParamSet& requested, const ResolveInput&)> resolve;
  // Where the defaults depart from the technique's paper: the values that run
  // the published algorithm. The registry then adds a parameter `preset`
  // (none or paper); with preset=paper these values replace the defaults of
  // every parameter the user did not set, before the resolution rule runs.
  RawParams paper_preset;
  std::function<std::unique_ptr<Technique>(const ParamSet&)> create;
  // Storage for a frame of the given content, for techniques whose storage
  // grows with the frame beyond a few W x H textures; empty: never tiled.
  std::function<StorageNeed(const ParamSet&, const FrameContent&)> storage_need;
  // Pixels of margin a tile needs so that every pixel inside it sees all it
  // depends on (neighbour searches, diffusion); 0 for per-pixel techniques.
  std::function<int(const ParamSet&)> tile_halo;
};

// The factory of a technique built from its validated parameters (or from
// nothing, for a technique without parameters): `.create = make_technique<T>`.
template <class T>
std::unique_ptr<Technique> make_technique(const ParamSet& params) {
  if constexpr (std::is_constructible_v<T, const ParamSet&>) return std::make_unique<T>(params);
  else return std::make_unique<T>();
}

// The parameters `input.given` as they run: the paper preset's values where
// preset=paper and the user set nothing, then the resolution rule's
// (TechniqueDescriptor::resolve); validated against the schema.
ParamSet resolve_params(const TechniqueDescriptor& technique, const ResolveInput& input);

// "" when a run can happen, otherwise the reason it cannot (device features,
// scene facts, or the technique's own check).
std::string supports(const TechniqueDescriptor& technique, const ParamSet& params, const DeviceProfile& device,
                     const SceneFacts& scene);

class TechniqueRegistry {
 public:
  void add(TechniqueDescriptor descriptor);
  const std::vector<TechniqueDescriptor>& all() const { return techniques_; }
  // The registered ids, in registration order.
  std::vector<std::string> ids() const;
  // Throws listing the registered ids when `id` is unknown.
  const TechniqueDescriptor& get(const std::string& id) const;
  const TechniqueDescriptor& reference() const;

 private:
  std::vector<TechniqueDescriptor> techniques_;
};

// Defined by the build-generated registry (algorithms/CMakeLists.txt).
TechniqueRegistry& builtin_techniques();

}  // namespace oit
