// depth_peeling, tie_break=triangle_id: front-to-back peeling in the order
// (view depth, stable triangle id), the reference's, so coplanar fragments
// come out the same whatever the submission order.
//
// One depth test cannot order by two 32-bit keys, so no depth test is used.
// A per-pixel state (by_id_shared.glsl) holds the key of the fragment the
// last pass selected and `next`, the nearest depth beyond it. Each geometry
// pass blends the selected fragment under the accumulation and reduces, with
// GL_MIN blending, the candidates for the following one: ties at the selected
// depth (by id), else the fragments at `next` (by id); plus the nearest depth
// beyond `next`. A full-screen resolve turns that into the new state. Pass 1
// only reduces the nearest depth, so depth complexity d costs d + 2 passes:
// the first selects nothing, the last composites the last fragment and
// selects nothing.
#include "algorithms/depth_peeling/by_triangle_id.h"

#include <algorithm>
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

constexpr GLuint kStateUnit = OIT_FIRST_TECHNIQUE_BINDING + 0;
constexpr GLuint kSelectUnit = OIT_FIRST_TECHNIQUE_BINDING + 1;
constexpr GLuint kAccumulationUnit = OIT_FIRST_TECHNIQUE_BINDING + 0;

// Per pixel: accumulation RGBA32F (16) + two RGBA32UI states (ping-pong,
// 2 x 16; 12 bytes used, RGB32UI is not required to be renderable) + the
// RG32F GL_MIN target (8).
constexpr uint64_t kBytesPerPixel = 16 + 2 * 16 + 8;

GLuint float_bits(float value) {
  GLuint bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

class DepthPeelingByTriangleId final : public Technique {
 public:
  DepthPeelingByTriangleId(int max_passes, bool early_exit)
      : max_passes_(max_passes),
        early_exit_(early_exit),
        init_(build_geometry_program("algorithms/depth_peeling/init_by_id.frag")),
        peel_(build_geometry_program("algorithms/depth_peeling/peel_by_id.frag")),
        resolve_(build_fullscreen_program("algorithms/depth_peeling/resolve_by_id.frag")),
        compose_(build_fullscreen_program("algorithms/depth_peeling/compose.frag")),
        fragments_query_(make_query(GL_SAMPLES_PASSED)) {}

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    accumulation_ = make_texture_2d(GL_RGBA32F, width, height);
    select_ = make_texture_2d(GL_RG32F, width, height);
    peel_target_ = make_framebuffer();
    glNamedFramebufferTexture(peel_target_.id(), GL_COLOR_ATTACHMENT0, accumulation_.id(), 0);
    glNamedFramebufferTexture(peel_target_.id(), GL_COLOR_ATTACHMENT1, select_.id(), 0);
    const GLenum two[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(peel_target_.id(), 2, two);
    check_complete(peel_target_, "peel");
    for (int i = 0; i < 2; ++i) {
      state_[i] = make_texture_2d(GL_RGBA32UI, width, height);
      state_targets_[i] = make_framebuffer();
      glNamedFramebufferTexture(state_targets_[i].id(), GL_COLOR_ATTACHMENT0, state_[i].id(), 0);
      check_complete(state_targets_[i], "state");
    }
    // Pass 1 writes only the reductions (the nearest depth).
    init_target_ = make_framebuffer();
    glNamedFramebufferTexture(init_target_.id(), GL_COLOR_ATTACHMENT0, select_.id(), 0);
    check_complete(init_target_, "nearest depth");
    gl_check("allocating depth peeling (triangle_id) targets of " + std::to_string(width) + "x" +
             std::to_string(height));
  }

  void render(const Frame& frame) override {
    check_triangle_ids(frame.scene.scene());
    passes_ = 0;
    const float infinity = std::numeric_limits<float>::infinity();
    // Selected (depth, id) and next depth: before pass 1, and where nothing is left.
    const GLuint nothing_selected_yet[4] = {float_bits(-infinity), 0, float_bits(-infinity), 0};
    const GLuint nothing_here[4] = {float_bits(infinity), 0, float_bits(infinity), 0};
    const GLfloat no_candidate[4] = {infinity, infinity, 0.0f, 0.0f};
    {
      auto clear = frame.clock.stage("clear");
      const GLfloat nothing_accumulated[4] = {0.0f, 0.0f, 0.0f, 1.0f};  // rgb, transmittance
      glClearNamedFramebufferfv(peel_target_.id(), GL_COLOR, 0, nothing_accumulated);
      glClearNamedFramebufferuiv(state_targets_[0].id(), GL_COLOR, 0, nothing_selected_yet);
    }
    for (const Program* program : {&init_, &peel_, &resolve_, &compose_}) frame.set_shared_uniforms(program->id());
    glViewport(0, 0, width_, height_);
    for (int pass = 1; pass <= max_passes_; ++pass) {
      auto peel = frame.clock.stage("peel");
      // Pass p writes state p % 2 and reads the one pass p - 1 wrote.
      const int current = pass % 2, previous = 1 - current;
      glClearNamedFramebufferfv(peel_target_.id(), GL_COLOR, 1, no_candidate);
      glEnable(GL_BLEND);
      if (pass == 1) {
        glBindFramebuffer(GL_FRAMEBUFFER, init_target_.id());
        glBlendEquation(GL_MIN);
        glUseProgram(init_.id());
        // Nothing is discarded and there is no depth test: this counts every fragment.
        glBeginQuery(GL_SAMPLES_PASSED, fragments_query_.id());
        frame.scene.draw();
        glEndQuery(GL_SAMPLES_PASSED);
      } else {
        glBindFramebuffer(GL_FRAMEBUFFER, peel_target_.id());
        // Accumulation, under: rgb += transmittance (dst alpha) * premultiplied; alpha *= 1 - a.
        glBlendEquationi(0, GL_FUNC_ADD);
        glBlendFuncSeparatei(0, GL_DST_ALPHA, GL_ONE, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
        glBlendEquationi(1, GL_MIN);
        glUseProgram(peel_.id());
        glBindTextureUnit(kStateUnit, state_[previous].id());
        frame.scene.draw();
      }
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
      glBindTextureUnit(kAccumulationUnit, accumulation_.id());
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }

  TechniqueCounters counters() const override {
    TechniqueCounters c;
    c.bytes_allocated = uint64_t(width_) * uint64_t(height_) * kBytesPerPixel;
    c.passes = passes_;
    // Geometry passes early exit did not run (without it all max_passes run).
    c.work_saved = {{"passes_avoided", early_exit_ ? double(uint64_t(max_passes_) - passes_) : 0.0}};
    // Read lazily, so no frame waits for them. Pass p's selection is
    // composited by pass p + 1: passes 2 .. passes - 1 count.
    GLuint fragments = 0;
    if (passes_ > 0) glGetQueryObjectuiv(fragments_query_.id(), GL_QUERY_RESULT, &fragments);
    const uint64_t composited = selected_queries_.sum(2, passes_);
    c.fragments_stored = composited;
    // Whatever was not composited: the passes ran out (or, never expected, a
    // fragment fell between the selected and the next depth).
    c.fragments_dropped = fragments > composited ? fragments - composited : 0;
    return c;
  }

 private:
  // Writes state `current` from state `previous` and the pass's reductions;
  // returns whether any pixel selected a fragment (after pass 1: has a
  // fragment; waits for the pass when early exit needs to know).
  bool resolve(int current, int previous, int pass, const GLuint nothing_here[4]) {
    const Query& query = selected_queries_.at(size_t(pass));
    glClearNamedFramebufferuiv(state_targets_[current].id(), GL_COLOR, 0, nothing_here);
    glBindFramebuffer(GL_FRAMEBUFFER, state_targets_[current].id());
    glUseProgram(resolve_.id());
    glBindTextureUnit(kStateUnit, state_[previous].id());
    glBindTextureUnit(kSelectUnit, select_.id());
    glBeginQuery(GL_SAMPLES_PASSED, query.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEndQuery(GL_SAMPLES_PASSED);
    return !early_exit_ || selected_queries_.result(size_t(pass)) != 0;
  }

  // The candidate keys rank ids up to kDepthPeelingMaxTriangleId; checked
  // once per uploaded scene.
  void check_triangle_ids(const Scene& scene) {
    if (&scene == checked_scene_ && scene.triangle_ids.data() == checked_ids_) return;
    const auto largest = std::max_element(scene.triangle_ids.begin(), scene.triangle_ids.end());
    if (largest != scene.triangle_ids.end() && *largest > kDepthPeelingMaxTriangleId) {
      throw std::runtime_error("depth_peeling: tie_break=triangle_id ranks stable triangle ids up to " +
                               std::to_string(kDepthPeelingMaxTriangleId) + "; scene '" + scene.name +
                               "' has id " + std::to_string(*largest) + " (use tie_break=submission)");
    }
    checked_scene_ = &scene;
    checked_ids_ = scene.triangle_ids.data();
  }

  static void check_complete(const Framebuffer& framebuffer, const char* what) {
    if (glCheckNamedFramebufferStatus(framebuffer.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw GlError(std::string("depth_peeling: the ") + what + " framebuffer is incomplete");
  }

  int max_passes_;
  bool early_exit_;
  Program init_, peel_, resolve_, compose_;
  Query fragments_query_;
  PassSampleQueries selected_queries_;  // pass p's resolve: fragments selected
  Texture accumulation_, select_, state_[2];
  Framebuffer peel_target_, state_targets_[2], init_target_;
  const Scene* checked_scene_ = nullptr;
  const uint32_t* checked_ids_ = nullptr;
  int width_ = 0, height_ = 0;
  uint64_t passes_ = 0;
};

}  // namespace

std::unique_ptr<Technique> make_depth_peeling_by_triangle_id(int max_passes, bool early_exit) {
  return std::make_unique<DepthPeelingByTriangleId>(max_passes, early_exit);
}

}  // namespace oit
