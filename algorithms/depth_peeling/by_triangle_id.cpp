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

#include <limits>
#include <string>
#include <vector>

#include "harness/toolkit/passes.h"
#include "harness/toolkit/peeling.h"
#include "harness/gl/check.h"
#include "harness/gl/pass_queries.h"
#include "harness/gl/shader_program.h"
#include "algorithms/depth_peeling/bindings.h"

namespace oit {
namespace {

// Per pixel: accumulation RGBA32F (16) + two RGBA32UI states (ping-pong,
// 2 x 16; 12 bytes used, RGB32UI is not required to be renderable) + the
// RG32F GL_MIN target (8).
constexpr uint64_t kBytesPerPixel = 16 + 2 * 16 + 8;

class DepthPeelingByTriangleId final : public TriangleIdPeeler {
 public:
  DepthPeelingByTriangleId(int max_passes, bool early_exit)
      : TriangleIdPeeler("depth_peeling", kDepthPeelingMaxTriangleId, max_passes, early_exit, kBytesPerPixel),
        init_(build_geometry_program("algorithms/depth_peeling/init_by_id.frag")),
        peel_(build_geometry_program("algorithms/depth_peeling/peel_by_id.frag")),
        resolve_(build_fullscreen_program("algorithms/depth_peeling/resolve_by_id.frag")),
        compose_(build_fullscreen_program("algorithms/depth_peeling/compose.frag")) {}

  void resize(int width, int height) override {
    set_size(width, height);
    accumulation_ = make_texture_2d(GL_RGBA32F, width, height);
    select_ = make_texture_2d(GL_RG32F, width, height);
    peel_target_ = make_target_framebuffer({&accumulation_, &select_}, "depth_peeling: the peel framebuffer");
    for (int i = 0; i < 2; ++i) {
      state_[i] = make_texture_2d(GL_RGBA32UI, width, height);
      state_targets_[i] = make_target_framebuffer({&state_[i]}, "depth_peeling: the state framebuffer");
    }
    // Pass 1 writes only the reductions (the nearest depth).
    init_target_ = make_target_framebuffer({&select_}, "depth_peeling: the nearest depth framebuffer");
    gl_check("allocating depth peeling (triangle_id) targets of " + std::to_string(width) + "x" +
             std::to_string(height));
  }

  void render(const Frame& frame) override {
    begin_frame(frame);
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
      if (pass == 1) {
        draw_counting_init_pass(frame, init_, init_target_, GL_MIN);
      } else {
        glEnable(GL_BLEND);
        glBindFramebuffer(GL_FRAMEBUFFER, peel_target_.id());
        // Accumulation, under: rgb += transmittance (dst alpha) * premultiplied; alpha *= 1 - a.
        glBlendEquationi(0, GL_FUNC_ADD);
        glBlendFuncSeparatei(0, GL_DST_ALPHA, GL_ONE, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
        glBlendEquationi(1, GL_MIN);
        glUseProgram(peel_.id());
        glBindTextureUnit(DP_ID_STATE_UNIT, state_[previous].id());
        frame.scene.draw();
        glDisable(GL_BLEND);
      }
      if (!continue_after(pass, [&] { return resolve(current, previous, pass, nothing_here); })) break;
    }
    compose(frame, compose_, {&accumulation_});
  }

 private:
  // Writes state `current` from state `previous` and the pass's reductions;
  // returns whether any pixel selected a fragment (after pass 1: has a
  // fragment; waits for the pass when early exit needs to know).
  bool resolve(int current, int previous, int pass, const GLuint nothing_here[4]) {
    glBindTextureUnit(DP_ID_STATE_UNIT, state_[previous].id());
    glBindTextureUnit(DP_ID_SELECT_UNIT, select_.id());
    resolve_selection(state_targets_[current], nothing_here, resolve_, selected_queries_.at(size_t(pass)),
                      [] { glDrawArrays(GL_TRIANGLES, 0, 3); });
    return selected_anything(pass);
  }

  Program init_, peel_, resolve_, compose_;
  Texture accumulation_, select_, state_[2];
  Framebuffer peel_target_, state_targets_[2], init_target_;
};

}  // namespace

std::unique_ptr<Technique> make_depth_peeling_by_triangle_id(int max_passes, bool early_exit) {
  return std::make_unique<DepthPeelingByTriangleId>(max_passes, early_exit);
}

}  // namespace oit
