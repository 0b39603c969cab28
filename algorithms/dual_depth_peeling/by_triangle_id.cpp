// dual_depth_peeling, tie_break=triangle_id: min-max peeling in the order
// (view depth, stable triangle id), the reference's, so coplanar fragments
// come out the same whatever the submission order.
//
// A min-max depth pass finds only the tied depth, not which tied fragment
// comes first, so the state (by_id_shared.glsl) holds the keys (depth, id) of
// the front and back fragments the last pass selected, and the depth next to
// each. Each geometry pass blends the two selected fragments into the front
// and back accumulations and reduces, with GL_MIN blending, the candidates
// for the next ones among the fragments strictly between the keys; a
// full-screen resolve turns that into the new state. Pass 1 is the min-max
// pass (init.frag), which selects nothing, so depth complexity d costs
// ceil(d / 2) + 2 passes: the last composites and selects nothing.
#include "algorithms/dual_depth_peeling/by_triangle_id.h"

#include <algorithm>
#include <cfloat>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "harness/gl/check.h"
#include "harness/gl/pass_queries.h"
#include "harness/gl/shader_program.h"
#include "shaders/bindings.h"

namespace oit {
namespace {

constexpr GLuint kKeysUnit = OIT_FIRST_TECHNIQUE_BINDING + 0;
constexpr GLuint kNextUnit = OIT_FIRST_TECHNIQUE_BINDING + 1;
constexpr GLuint kSelectUnit = OIT_FIRST_TECHNIQUE_BINDING + 2;
constexpr GLuint kFrontUnit = OIT_FIRST_TECHNIQUE_BINDING + 0;
constexpr GLuint kBackUnit = OIT_FIRST_TECHNIQUE_BINDING + 1;
constexpr GLint kCountBackUniform = OIT_FIRST_TECHNIQUE_UNIFORM;

// Per pixel: front and back accumulations RGBA32F (2 x 16) + two RGBA32UI
// selected keys (2 x 16) + two RG32F next depths (2 x 8), both ping-pong +
// the RGBA32F GL_MIN target (16).
constexpr uint64_t kBytesPerPixel = 2 * 16 + 2 * 16 + 2 * 8 + 16;

GLuint float_bits(float value) {
  GLuint bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

class DualDepthPeelingByTriangleId final : public Technique {
 public:
  DualDepthPeelingByTriangleId(int max_passes, bool early_exit)
      : max_passes_(max_passes),
        early_exit_(early_exit),
        init_(build_geometry_program("algorithms/dual_depth_peeling/init.frag", {{"COUNT_LEFT_UNPEELED", "0"}})),
        peel_(build_geometry_program("algorithms/dual_depth_peeling/peel_by_id.frag")),
        resolve_(build_fullscreen_program("algorithms/dual_depth_peeling/resolve_by_id.frag")),
        compose_(build_fullscreen_program("algorithms/dual_depth_peeling/compose.frag")),
        fragments_query_(make_query(GL_SAMPLES_PASSED)) {}

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    front_ = make_texture_2d(GL_RGBA32F, width, height);
    back_ = make_texture_2d(GL_RGBA32F, width, height);
    select_ = make_texture_2d(GL_RGBA32F, width, height);
    peel_target_ = make_framebuffer();
    const Texture* peel_outputs[] = {&front_, &back_, &select_};
    for (int i = 0; i < 3; ++i)
      glNamedFramebufferTexture(peel_target_.id(), GL_COLOR_ATTACHMENT0 + i, peel_outputs[i]->id(), 0);
    const GLenum draw_buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glNamedFramebufferDrawBuffers(peel_target_.id(), 3, draw_buffers);
    check_complete(peel_target_, "peel");
    for (int i = 0; i < 2; ++i) {
      keys_[i] = make_texture_2d(GL_RGBA32UI, width, height);
      next_[i] = make_texture_2d(GL_RG32F, width, height);
      state_targets_[i] = make_framebuffer();
      glNamedFramebufferTexture(state_targets_[i].id(), GL_COLOR_ATTACHMENT0, keys_[i].id(), 0);
      glNamedFramebufferTexture(state_targets_[i].id(), GL_COLOR_ATTACHMENT1, next_[i].id(), 0);
      glNamedFramebufferDrawBuffers(state_targets_[i].id(), 2, draw_buffers);
      check_complete(state_targets_[i], "state");
    }
    // Pass 1 writes only the next depths of state 1: (-nearest, farthest).
    init_target_ = make_framebuffer();
    glNamedFramebufferTexture(init_target_.id(), GL_COLOR_ATTACHMENT0, next_[1].id(), 0);
    check_complete(init_target_, "depth range");
    gl_check("allocating dual depth peeling (triangle_id) targets of " + std::to_string(width) + "x" +
             std::to_string(height));
  }

  void render(const Frame& frame) override {
    check_triangle_ids(frame.scene.scene());
    passes_ = 0;
    const float infinity = std::numeric_limits<float>::infinity();
    // Keys (front depth, id, back depth, id): everything lies between -inf and +inf ...
    const GLuint nothing_selected_yet[4] = {float_bits(-infinity), 0, float_bits(infinity), 0};
    // ... and nothing between +inf and -inf.
    const GLuint nothing_here[4] = {float_bits(infinity), 0, float_bits(-infinity), 0};
    const GLfloat no_candidate[4] = {infinity, infinity, infinity, infinity};
    {
      auto clear = frame.clock.stage("clear");
      const GLfloat nothing_accumulated[4] = {0.0f, 0.0f, 0.0f, 1.0f};  // rgb, transmittance
      glClearNamedFramebufferfv(peel_target_.id(), GL_COLOR, 0, nothing_accumulated);
      glClearNamedFramebufferfv(peel_target_.id(), GL_COLOR, 1, nothing_accumulated);
      glClearNamedFramebufferuiv(state_targets_[1].id(), GL_COLOR, 0, nothing_selected_yet);
      const GLfloat empty_range[4] = {-FLT_MAX, -FLT_MAX, 0.0f, 0.0f};  // identity of GL_MAX
      glClearNamedFramebufferfv(state_targets_[1].id(), GL_COLOR, 1, empty_range);
    }
    for (const Program* program : {&init_, &peel_, &resolve_, &compose_}) frame.set_shared_uniforms(program->id());
    glViewport(0, 0, width_, height_);
    for (int pass = 1; pass <= max_passes_; ++pass) {
      auto peel = frame.clock.stage("peel");
      // Pass p writes state p % 2 and reads the one pass p - 1 wrote.
      const int current = pass % 2, previous = 1 - current;
      glEnable(GL_BLEND);
      if (pass == 1) {
        glBindFramebuffer(GL_FRAMEBUFFER, init_target_.id());
        glBlendEquation(GL_MAX);
        glUseProgram(init_.id());
        // Nothing is discarded and there is no depth test: this counts every fragment.
        glBeginQuery(GL_SAMPLES_PASSED, fragments_query_.id());
        frame.scene.draw();
        glEndQuery(GL_SAMPLES_PASSED);
        ++passes_;
        glDisable(GL_BLEND);
        continue;
      }
      glClearNamedFramebufferfv(peel_target_.id(), GL_COLOR, 2, no_candidate);
      glBindFramebuffer(GL_FRAMEBUFFER, peel_target_.id());
      // Front, under: rgb += transmittance (dst alpha) * premultiplied; alpha *= 1 - a.
      glBlendEquationi(0, GL_FUNC_ADD);
      glBlendFuncSeparatei(0, GL_DST_ALPHA, GL_ONE, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
      // Back, over: rgb = a * c + (1 - a) * rgb; alpha (transmittance) *= 1 - a.
      glBlendEquationi(1, GL_FUNC_ADD);
      glBlendFuncSeparatei(1, GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
      glBlendEquationi(2, GL_MIN);
      glUseProgram(peel_.id());
      glBindTextureUnit(kKeysUnit, keys_[previous].id());
      glBindTextureUnit(kNextUnit, next_[previous].id());
      frame.scene.draw();
      ++passes_;
      glDisable(GL_BLEND);
      // What the last allowed pass selects is never composited: no state needed.
      if (pass == max_passes_) break;
      if (!resolve(current, previous, pass, nothing_here) && early_exit_) break;
    }
    glBlendEquation(GL_FUNC_ADD);  // GL's defaults, which other techniques may assume
    glBlendFunc(GL_ONE, GL_ZERO);
    {
      auto compose = frame.clock.stage("compose");
      frame.bind_target();
      glUseProgram(compose_.id());
      glBindTextureUnit(kFrontUnit, front_.id());
      glBindTextureUnit(kBackUnit, back_.id());
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }

  TechniqueCounters counters() const override {
    TechniqueCounters c;
    c.bytes_allocated = uint64_t(width_) * uint64_t(height_) * kBytesPerPixel;
    c.passes = passes_;
    // Geometry passes early exit did not run (without it all max_passes run).
    c.work_saved = {{"passes_avoided", early_exit_ ? double(uint64_t(max_passes_) - passes_) : 0.0}};
    // Read lazily, so no frame waits for them. Pass p's selections are
    // composited by pass p + 1: passes 2 .. passes - 1 count.
    GLuint fragments = 0;
    if (passes_ > 0) glGetQueryObjectuiv(fragments_query_.id(), GL_QUERY_RESULT, &fragments);
    const uint64_t composited = selected_queries_.sum(2, passes_);
    c.fragments_stored = composited;
    // Whatever was not composited: the middle layers when the passes ran out.
    c.fragments_dropped = fragments > composited ? fragments - composited : 0;
    return c;
  }

 private:
  // Writes state `current` from state `previous` and the pass's reductions;
  // returns whether any pixel selected a fragment (waits for the pass when
  // early exit needs to know).
  bool resolve(int current, int previous, int pass, const GLuint nothing_here[4]) {
    const Query& query = selected_queries_.at(size_t(pass));
    glClearNamedFramebufferuiv(state_targets_[current].id(), GL_COLOR, 0, nothing_here);
    glBindFramebuffer(GL_FRAMEBUFFER, state_targets_[current].id());
    glUseProgram(resolve_.id());
    glBindTextureUnit(kKeysUnit, keys_[previous].id());
    glBindTextureUnit(kNextUnit, next_[previous].id());
    glBindTextureUnit(kSelectUnit, select_.id());
    glBeginQuery(GL_SAMPLES_PASSED, query.id());
    for (GLint count_back : {0, 1}) {
      glProgramUniform1i(resolve_.id(), kCountBackUniform, count_back);
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glEndQuery(GL_SAMPLES_PASSED);
    return !early_exit_ || selected_queries_.result(size_t(pass)) != 0;
  }

  // The candidate keys rank ids up to kDualDepthPeelingMaxTriangleId;
  // checked once per uploaded scene.
  void check_triangle_ids(const Scene& scene) {
    if (&scene == checked_scene_ && scene.triangle_ids.data() == checked_ids_) return;
    const auto largest = std::max_element(scene.triangle_ids.begin(), scene.triangle_ids.end());
    if (largest != scene.triangle_ids.end() && *largest > kDualDepthPeelingMaxTriangleId) {
      throw std::runtime_error("dual_depth_peeling: tie_break=triangle_id ranks stable triangle ids up to " +
                               std::to_string(kDualDepthPeelingMaxTriangleId) + "; scene '" + scene.name +
                               "' has id " + std::to_string(*largest) + " (use tie_break=submission)");
    }
    checked_scene_ = &scene;
    checked_ids_ = scene.triangle_ids.data();
  }

  static void check_complete(const Framebuffer& framebuffer, const char* what) {
    if (glCheckNamedFramebufferStatus(framebuffer.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw GlError(std::string("dual_depth_peeling: the ") + what + " framebuffer is incomplete");
  }

  int max_passes_;
  bool early_exit_;
  Program init_, peel_, resolve_, compose_;
  Query fragments_query_;
  PassSampleQueries selected_queries_;  // pass p's resolve: fragments selected
  Texture front_, back_, select_, keys_[2], next_[2];
  Framebuffer peel_target_, state_targets_[2], init_target_;
  const Scene* checked_scene_ = nullptr;
  const uint32_t* checked_ids_ = nullptr;
  int width_ = 0, height_ = 0;
  uint64_t passes_ = 0;
};

}  // namespace

std::unique_ptr<Technique> make_dual_depth_peeling_by_triangle_id(int max_passes, bool early_exit) {
  return std::make_unique<DualDepthPeelingByTriangleId>(max_passes, early_exit);
}

}  // namespace oit
