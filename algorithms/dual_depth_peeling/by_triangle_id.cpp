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

#include <cfloat>
#include <limits>
#include <string>
#include <vector>

#include "harness/toolkit/passes.h"
#include "harness/toolkit/peeling.h"
#include "harness/gl/check.h"
#include "harness/gl/pass_queries.h"
#include "harness/gl/shader_program.h"
#include "harness/gl/uniforms.h"
#include "algorithms/dual_depth_peeling/bindings.h"

namespace oit {
namespace {

// Per pixel: front and back accumulations RGBA32F (2 x 16) + two RGBA32UI
// selected keys (2 x 16) + two RG32F next depths (2 x 8), both ping-pong +
// the RGBA32F GL_MIN target (16).
constexpr uint64_t kBytesPerPixel = 2 * 16 + 2 * 16 + 2 * 8 + 16;

class DualDepthPeelingByTriangleId final : public TriangleIdPeeler {
 public:
  DualDepthPeelingByTriangleId(int max_passes, bool early_exit)
      : TriangleIdPeeler("dual_depth_peeling", kDualDepthPeelingMaxTriangleId, max_passes, early_exit, kBytesPerPixel),
        init_(build_geometry_program("algorithms/dual_depth_peeling/init.frag", {{"COUNT_LEFT_UNPEELED", "0"}})),
        peel_(build_geometry_program("algorithms/dual_depth_peeling/peel_by_id.frag")),
        resolve_(build_fullscreen_program("algorithms/dual_depth_peeling/resolve_by_id.frag")),
        compose_(build_fullscreen_program("algorithms/dual_depth_peeling/compose.frag")) {}

  void resize(int width, int height) override {
    set_size(width, height);
    front_ = make_texture_2d(GL_RGBA32F, width, height);
    back_ = make_texture_2d(GL_RGBA32F, width, height);
    select_ = make_texture_2d(GL_RGBA32F, width, height);
    peel_target_ = make_target_framebuffer({&front_, &back_, &select_}, "dual_depth_peeling: the peel framebuffer");
    for (int i = 0; i < 2; ++i) {
      keys_[i] = make_texture_2d(GL_RGBA32UI, width, height);
      next_[i] = make_texture_2d(GL_RG32F, width, height);
      state_targets_[i] = make_target_framebuffer({&keys_[i], &next_[i]}, "dual_depth_peeling: the state framebuffer");
    }
    // Pass 1 writes only the next depths of state 1: (-nearest, farthest).
    init_target_ = make_target_framebuffer({&next_[1]}, "dual_depth_peeling: the depth range framebuffer");
    gl_check("allocating dual depth peeling (triangle_id) targets of " + std::to_string(width) + "x" +
             std::to_string(height));
  }

  void render(const Frame& frame) override {
    begin_frame(frame);
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
      if (pass == 1) {
        draw_counting_init_pass(frame, init_, init_target_, GL_MAX);
        ++passes_;
        continue;
      }
      glEnable(GL_BLEND);
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
      glBindTextureUnit(DUAL_ID_KEYS_UNIT, keys_[previous].id());
      glBindTextureUnit(DUAL_ID_NEXT_UNIT, next_[previous].id());
      frame.scene.draw();
      glDisable(GL_BLEND);
      if (!continue_after(pass, [&] { return resolve(current, previous, pass, nothing_here); })) break;
    }
    compose(frame, compose_, {&front_, &back_});
  }

 private:
  // Writes state `current` from state `previous` and the pass's reductions;
  // returns whether any pixel selected a fragment (waits for the pass when
  // early exit needs to know).
  bool resolve(int current, int previous, int pass, const GLuint nothing_here[4]) {
    glBindTextureUnit(DUAL_ID_KEYS_UNIT, keys_[previous].id());
    glBindTextureUnit(DUAL_ID_NEXT_UNIT, next_[previous].id());
    glBindTextureUnit(DUAL_ID_SELECT_UNIT, select_.id());
    resolve_selection(state_targets_[current], nothing_here, resolve_, selected_queries_.at(size_t(pass)), [this] {
      for (GLint count_back : {0, 1}) {
        set_uniform(resolve_.id(), DUAL_ID_COUNT_BACK_UNIFORM, count_back);
        glDrawArrays(GL_TRIANGLES, 0, 3);
      }
    });
    return selected_anything(pass);
  }

  Program init_, peel_, resolve_, compose_;
  Texture front_, back_, select_, keys_[2], next_[2];
  Framebuffer peel_target_, state_targets_[2], init_target_;
};

}  // namespace

std::unique_ptr<Technique> make_dual_depth_peeling_by_triangle_id(int max_passes, bool early_exit) {
  return std::make_unique<DualDepthPeelingByTriangleId>(max_passes, early_exit);
}

}  // namespace oit
