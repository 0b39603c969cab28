#include "core/runner.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <sstream>

#include "core/memory_failure.h"
#include "core/system_load.h"
#include "gl/check.h"
#include "model_files.h"
#include "scene_library.h"

namespace oit {

std::string to_string(RunStatus status) {
  switch (status) {
    case RunStatus::ok: return "ok";
    case RunStatus::skipped: return "skipped";
    case RunStatus::error: return "error";
  }
  return "?";
}

const StageResult* RunResult::stage(const std::string& name, const std::string& clock_name) const {
  for (const auto& s : stages)
    if (s.stage == name && s.clock == clock_name) return &s;
  return nullptr;
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

// Default GL state every technique may assume at the start of a frame.
void reset_gl_state() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glUseProgram(0);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_SCISSOR_TEST);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

}  // namespace

RenderTarget::RenderTarget(int width, int height) {
  color = make_texture_2d(GL_RGBA32F, width, height);
  framebuffer = make_framebuffer();
  glNamedFramebufferTexture(framebuffer.id(), GL_COLOR_ATTACHMENT0, color.id(), 0);
  if (glCheckNamedFramebufferStatus(framebuffer.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw GlError("RGBA32F render target of " + std::to_string(width) + "x" + std::to_string(height) +
                  " is incomplete (the device could not allocate it)");
  }
}

ScreenRect scene_rect_of(const Frame& frame) {
  return projected_scene_rect(frame.scene.bounding_box(), frame.projection * frame.view, frame.width, frame.height);
}

ScreenRect render_frame(Technique& technique, const Frame& frame, bool record, bool scene_rect) {
  reset_gl_state();
  // Before the scissor: the pixels the scene cannot reach show the background.
  const GLfloat clear_color[4] = {frame.background.r, frame.background.g, frame.background.b, 0.0f};
  glClearNamedFramebufferfv(frame.target_framebuffer, GL_COLOR, 0, clear_color);
  const ScreenRect rect = scene_rect ? scene_rect_of(frame) : ScreenRect{0, 0, frame.width, frame.height};
  if (scene_rect) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(rect.x, rect.y, rect.width, rect.height);
  }
  frame.clock.begin_frame(record);
  {
    auto total = frame.clock.stage("total");
    frame.scene.bind();
    technique.render(frame);
  }
  frame.clock.end_frame();
  reset_gl_state();
  return rect;
}

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
                                      int height, const glm::vec3& background, const std::string& camera) {
  LoadedScene& loaded = scene(scene_spec, scene_params, "original", camera);
  std::ostringstream key;
  key << loaded.hash << "|" << width << "x" << height << "|" << background.r << "," << background.g << ","
      << background.b;
  auto it = references_.find(key.str());
  if (it != references_.end()) return it->second;
  if (auto cached = reference_cache_.load(key.str())) {
    ++references_loaded_;
    return references_.emplace(key.str(), std::move(*cached)).first->second;
  }
  RunSpec spec;
  spec.technique = registry_.reference().id;
  spec.scene = scene_spec;
  spec.scene_params = scene_params;
  spec.camera = camera;
  spec.width = width;
  spec.height = height;
  spec.warmup = 0;
  spec.frames = 1;
  spec.clock = ClockKind::wall;
  spec.background = background;
  spec.scene_rect = false;  // the reference does not depend on the harness's shortcuts
  RunResult result;
  result.spec = spec;
  execute(spec, result);
  ++references_rendered_;
  reference_cache_.store(key.str(), result.image);
  return references_.emplace(key.str(), std::move(result.image)).first->second;
}

RunResult Harness::run(const RunSpec& spec) {
  RunResult result;
  result.spec = spec;
  result.clock = spec.clock.value_or(default_clock());
  try {
    const TechniqueDescriptor& technique = registry_.get(spec.technique);
    const ParamSet params(technique.params, spec.params, "technique '" + spec.technique + "'");
    result.technique_params = params.canonical();
    if (spec.width < 1 || spec.height < 1 || spec.width > 16384 || spec.height > 16384) {
      throw std::invalid_argument("size " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                                  " is outside 1x1 .. 16384x16384");
    }
    if (spec.frames < 1 || spec.warmup < 0) throw std::invalid_argument("frames must be >= 1 and warmup >= 0");
    // Known before the scene loads, so a skipped row (a model not
    // installed) carries it too and `bench --resume` can find it.
    result.scene_params = canonical_scene_params(spec.scene, spec.scene_params);
    LoadedScene& loaded = scene(spec.scene, spec.scene_params, spec.submission_order, spec.camera);
    result.scene_params = loaded.scene.params;
    const SceneFacts facts{loaded.scene.triangle_count(), loaded.scene.object_count, true};
    if (std::string reason = supports(technique, params, device(), facts); !reason.empty()) {
      result.status = RunStatus::skipped;
      result.message = reason;
      return result;
    }
    OtherProcessLoad load;
    load.start();
    execute(spec, result);
    result.other_process_load = load.stop();
    result.noisy = result.other_process_load > kNoisyLoadThreshold;
    // The scene's size goes with every row so plots against triangles or
    // vertices (carnecky2013 Fig. 15, pastyrik2016 Fig. 9) need only the CSV.
    result.counters.extra.emplace_back("scene_triangles", double(loaded.scene.triangle_count()));
    result.counters.extra.emplace_back("scene_vertices", double(loaded.scene.vertices.size()));

    const std::string size_key = std::to_string(spec.width) + "x" + std::to_string(spec.height);
    auto complexity = loaded.complexity.find(size_key);
    if (complexity == loaded.complexity.end()) {
      const glm::mat4 projection = loaded.scene.camera.projection(float(spec.width) / float(spec.height));
      complexity = loaded.complexity
                       .emplace(size_key, measure_depth_complexity(*loaded.gpu, loaded.scene.camera.view, projection,
                                                                   spec.width, spec.height))
                       .first;
    }
    result.scene_fragments = complexity->second.fragments;
    result.max_depth_complexity = complexity->second.max;
    result.mean_depth_complexity = complexity->second.mean;
    result.psi = complexity->second.psi;
    result.error = compare_images(result.image, reference_image(spec.scene, spec.scene_params, spec.width, spec.height,
                                                                spec.background, spec.camera));
  } catch (const MissingModel& e) {
    result.status = RunStatus::skipped;  // an optional model not installed here
    result.message = e.what();
  } catch (const std::exception& e) {
    result.status = RunStatus::error;
    result.message = explain_failure(e, spec.width, spec.height);  // a memory failure names the size and remedy
    while (glGetError() != GL_NO_ERROR) {
    }
    reset_gl_state();
  }
  return result;
}

void Harness::execute(const RunSpec& spec, RunResult& result) {
  const TechniqueDescriptor& descriptor = registry_.get(spec.technique);
  const ParamSet params(descriptor.params, spec.params, "technique '" + spec.technique + "'");
  LoadedScene& loaded = scene(spec.scene, spec.scene_params, spec.submission_order, spec.camera);
  const ClockKind clock_kind = spec.clock.value_or(default_clock());
  result.clock = clock_kind;

  std::unique_ptr<Technique> technique = descriptor.create(params);
  technique->resize(spec.width, spec.height);
  RenderTarget target(spec.width, spec.height);
  StageClock clock(clock_kind);
  const float aspect = float(spec.width) / float(spec.height);
  const Frame frame{*loaded.gpu,  loaded.scene.camera.view,   loaded.scene.camera.projection(aspect),
                    spec.width,   spec.height,                spec.background,
                    target.framebuffer.id(), clock};
  ScreenRect rect;
  for (int i = 0; i < spec.warmup + spec.frames; ++i) {
    rect = render_frame(*technique, frame, i >= spec.warmup, spec.scene_rect);
    gl_check("frame " + std::to_string(i) + " of " + spec.technique);
  }
  result.counters = technique->counters();
  // The harness's own adaptive path: pixels every full-screen pass skipped.
  if (spec.scene_rect) {
    result.counters.work_saved.emplace_back(kPixelsOutsideSceneRect,
                                            double(uint64_t(spec.width) * uint64_t(spec.height) - rect.pixels()));
  }
  result.image = read_texture_rgba32f(target.color.id(), spec.width, spec.height);
  gl_check("reading back the image of " + spec.technique);

  result.stages.clear();
  for (auto& [name, samples] : clock.results()) {
    if (clock_kind != ClockKind::gl)
      result.stages.push_back({name, "wall", summarize(samples.wall_ms), samples.wall_ms});
    if (clock_kind != ClockKind::wall) result.stages.push_back({name, "gl", summarize(samples.gl_ms), samples.gl_ms});
  }
  if (clock_kind == ClockKind::both) {
    const StageResult* wall = result.stage("total", "wall");
    const StageResult* gl = result.stage("total", "gl");
    if (wall && gl && wall->summary.median > 0.0)
      result.clock_disagreement = std::abs(gl->summary.median - wall->summary.median) / wall->summary.median;
  }
}

}  // namespace oit
