#include "harness/toolkit/peeling.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "harness/toolkit/passes.h"
#include "harness/gl/gl.h"
#include "shaders/bindings.h"

namespace oit {

uint32_t float_bits(float value) {
  uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

namespace {
// Which of two fragments at one depth comes first: the stable triangle id, or submission order.
enum class TieBreak { triangle_id, submission };
const Choices<TieBreak> kTieBreaks{{TieBreak::triangle_id, "triangle_id"}, {TieBreak::submission, "submission"}};

}  // namespace

TechniqueDescriptor describe_peeler(TechniqueDescriptor d, const PeelingText& text, uint64_t bytes_per_pixel,
                                    PeelerFactory by_triangle_id, PeelerFactory by_submission) {
  d.params = {
      ParamSpec::integer("max_passes", 64, 1, 4096, text.max_passes),
      ParamSpec::boolean("early_exit", true, text.early_exit),
      kTieBreaks.spec("tie_break", TieBreak::triangle_id, text.tie_break),
  };
  d.stages = {"clear", "peel", "compose"};
  d.exactness = Exactness::exact;
  // The papers peel by depth alone, a tie going to the first submitted.
  d.paper_preset = {{"tie_break", "submission"}};
  d.adaptive_switches = {{"early_exit", text.early_exit_saves, {{"early_exit", "true"}}, {{"early_exit", "false"}}}};
  d.storage_need = [bytes_per_pixel](const ParamSet&, const FrameContent& content) {
    return StorageNeed{0, content.pixels() * bytes_per_pixel};
  };
  d.create = [by_triangle_id, by_submission](const ParamSet& params) -> std::unique_ptr<Technique> {
    const int max_passes = int(params.integer("max_passes"));
    const bool early_exit = params.boolean("early_exit");
    if (params.choice("tie_break", kTieBreaks) == TieBreak::submission) return by_submission(max_passes, early_exit);
    return by_triangle_id(max_passes, early_exit);
  };
  return d;
}

TechniqueCounters peeling_counters(uint64_t bytes_allocated, uint64_t passes, int max_passes, bool early_exit) {
  TechniqueCounters c;
  c.bytes_allocated = bytes_allocated;
  c.passes = passes;
  c.work_saved = {{"passes_avoided", early_exit ? double(uint64_t(max_passes) - passes) : 0.0}};
  return c;
}

void count_selected_fragments(TechniqueCounters& c, const Query& all_fragments, const PassSampleQueries& selected) {
  GLuint fragments = 0;
  if (c.passes > 0) glGetQueryObjectuiv(all_fragments.id(), GL_QUERY_RESULT, &fragments);
  const uint64_t composited = selected.sum(2, c.passes);
  c.fragments_stored = composited;
  // Whatever was not composited: the passes ran out (or, never expected, a
  // fragment fell between the selected and the next depth).
  c.fragments_dropped = fragments > composited ? fragments - composited : 0;
}

void resolve_selection(const Framebuffer& state, const uint32_t nothing_here[4], const Program& resolve,
                       const Query& selected, const std::function<void()>& draw) {
  glClearNamedFramebufferuiv(state.id(), GL_COLOR, 0, nothing_here);
  glBindFramebuffer(GL_FRAMEBUFFER, state.id());
  glUseProgram(resolve.id());
  glBeginQuery(GL_SAMPLES_PASSED, selected.id());
  draw();
  glEndQuery(GL_SAMPLES_PASSED);
}

void restore_default_blending() {
  glDisable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ZERO);
}

TriangleIdPeeler::TriangleIdPeeler(std::string technique, uint32_t largest_id, int max_passes, bool early_exit,
                                   uint64_t bytes_per_pixel)
    : max_passes_(max_passes),
      early_exit_(early_exit),
      fragments_query_(make_query(GL_SAMPLES_PASSED)),
      triangle_ids_(std::move(technique), largest_id),
      bytes_per_pixel_(bytes_per_pixel) {}

void TriangleIdPeeler::begin_frame(const Frame& frame) {
  triangle_ids_.check(frame.scene);
  passes_ = 0;
}

bool TriangleIdPeeler::continue_after(int pass, const std::function<bool()>& resolve) {
  ++passes_;
  if (pass == max_passes_) return false;
  return resolve() || !early_exit_;
}

void TriangleIdPeeler::draw_counting_init_pass(const Frame& frame, const Program& init, const Framebuffer& target,
                                               GLenum reduction) const {
  glEnable(GL_BLEND);
  glBindFramebuffer(GL_FRAMEBUFFER, target.id());
  glBlendEquation(reduction);
  glUseProgram(init.id());
  glBeginQuery(GL_SAMPLES_PASSED, fragments_query_.id());
  frame.scene.draw();
  glEndQuery(GL_SAMPLES_PASSED);
  glDisable(GL_BLEND);
}

void TriangleIdPeeler::compose(const Frame& frame, const Program& program,
                               std::initializer_list<const Texture*> inputs) const {
  restore_default_blending();
  auto stage = frame.clock.stage("compose");
  GLuint unit = OIT_FIRST_TECHNIQUE_BINDING;
  for (const Texture* input : inputs) glBindTextureUnit(unit++, input->id());
  draw_fullscreen_pass(frame, program);
}

TechniqueCounters TriangleIdPeeler::counters() const {
  TechniqueCounters c =
      peeling_counters(uint64_t(width_) * uint64_t(height_) * bytes_per_pixel_, passes_, max_passes_, early_exit_);
  count_selected_fragments(c, fragments_query_, selected_queries_);
  return c;
}

void TriangleIdLimit::check(const SceneGpu& uploaded) {
  if (uploaded.serial() == checked_scene_) return;
  const Scene& scene = uploaded.scene();
  const auto largest = std::max_element(scene.triangle_ids.begin(), scene.triangle_ids.end());
  if (largest != scene.triangle_ids.end() && *largest > largest_id_) {
    throw std::runtime_error(technique_ + ": tie_break=triangle_id ranks stable triangle ids up to " +
                             std::to_string(largest_id_) + "; scene '" + scene.name + "' has id " +
                             std::to_string(*largest) + " (use tie_break=submission)");
  }
  checked_scene_ = uploaded.serial();
}

}  // namespace oit
