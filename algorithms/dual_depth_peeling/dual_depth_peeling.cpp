// dual_depth_peeling: min-max depth peeling (Bavoil & Myers 2008). A first
// geometry pass finds every pixel's nearest and farthest depth (RG32F under
// GL_MAX); each further pass composites the fragment at the nearest depth
// under the front accumulation and the one at the farthest depth over the
// back accumulation, while finding the next range among the fragments
// strictly inside. N layers cost N/2 + 1 geometry passes (rounded up).
//
// This file is tie_break=submission: fragments tied in depth are composited
// in the same pass, in submission order. tie_break=triangle_id (the default,
// by_triangle_id.cpp) composites them by stable triangle id, as the
// reference does.
#include <cfloat>
#include <stdexcept>
#include <string>

#include "algorithms/dual_depth_peeling/by_triangle_id.h"
#include "harness/toolkit/technique.h"
#include "harness/toolkit/passes.h"
#include "harness/toolkit/peeling.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"
#include "algorithms/dual_depth_peeling/bindings.h"

namespace oit {
namespace {

// Per pixel: two RG32F depth ranges (ping-pong, 2 x 8) + front and back
// accumulations RGBA32F (2 x 16).
constexpr uint64_t kBytesPerPixel = 2 * 8 + 2 * 16;
constexpr uint64_t kCounterBytes = sizeof(GLuint);

class DualDepthPeelingBySubmission final : public Technique {
 public:
  DualDepthPeelingBySubmission(int max_passes, bool early_exit)
      : max_passes_(max_passes),
        early_exit_(early_exit),
        // Variants with COUNT_LEFT_UNPEELED=1 serve the last pass max_passes allows.
        init_{build_geometry_program("algorithms/dual_depth_peeling/init.frag", {{"COUNT_LEFT_UNPEELED", "0"}}),
              build_geometry_program("algorithms/dual_depth_peeling/init.frag", {{"COUNT_LEFT_UNPEELED", "1"}})},
        peel_{build_geometry_program("algorithms/dual_depth_peeling/peel.frag", {{"COUNT_LEFT_UNPEELED", "0"}}),
              build_geometry_program("algorithms/dual_depth_peeling/peel.frag", {{"COUNT_LEFT_UNPEELED", "1"}})},
        range_check_(build_fullscreen_program("algorithms/dual_depth_peeling/range_check.frag")),
        compose_(build_fullscreen_program("algorithms/dual_depth_peeling/compose.frag")),
        counter_(make_buffer(kCounterBytes)),
        fragments_query_(make_query(GL_SAMPLES_PASSED)),
        any_range_query_(make_query(GL_ANY_SAMPLES_PASSED)) {}

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    front_ = make_texture_2d(GL_RGBA32F, width, height);
    back_ = make_texture_2d(GL_RGBA32F, width, height);
    for (int i = 0; i < 2; ++i) {
      ranges_[i] = make_texture_2d(GL_RG32F, width, height);
      range_targets_[i] = make_target_framebuffer({&ranges_[i]}, "dual_depth_peeling: the depth range framebuffer");
      peel_targets_[i] =
          make_target_framebuffer({&ranges_[i], &front_, &back_}, "dual_depth_peeling: the peel framebuffer");
    }
    // The range check writes nothing; it only needs a framebuffer of this size.
    no_attachments_ = make_attachmentless_framebuffer(width, height);
    gl_check("allocating dual depth peeling targets of " + std::to_string(width) + "x" + std::to_string(height));
  }

  void render(const Frame& frame) override {
    passes_ = 0;
    const GLfloat empty_range[4] = {-FLT_MAX, -FLT_MAX, 0.0f, 0.0f};
    {
      auto clear = frame.clock.stage("clear");
      // Front: nothing accumulated, transmittance 1; back: the same.
      const GLfloat nothing_accumulated[4] = {0.0f, 0.0f, 0.0f, 1.0f};
      glClearNamedFramebufferfv(peel_targets_[0].id(), GL_COLOR, 1, nothing_accumulated);
      glClearNamedFramebufferfv(peel_targets_[0].id(), GL_COLOR, 2, nothing_accumulated);
      fill_buffer_u32(counter_, 0);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DUAL_PEELING_COUNTER_BINDING, counter_.id());
    for (const Program* program : {&init_[0], &init_[1], &peel_[0], &peel_[1], &range_check_, &compose_})
      frame.set_shared_uniforms(program->id());
    glViewport(0, 0, width_, height_);
    glEnable(GL_BLEND);
    for (int pass = 1; pass <= max_passes_; ++pass) {
      auto peel = frame.clock.stage("peel");
      // Pass p writes range p % 2 and reads the one pass p - 1 wrote.
      const int current = pass % 2, previous = 1 - current;
      glClearNamedFramebufferfv(range_targets_[current].id(), GL_COLOR, 0, empty_range);
      const bool last_allowed = pass == max_passes_;
      if (pass == 1) {
        glBindFramebuffer(GL_FRAMEBUFFER, range_targets_[current].id());
        glBlendEquation(GL_MAX);
        glUseProgram(init_[last_allowed ? 1 : 0].id());
        // Nothing is discarded and there is no depth test: this counts every fragment.
        glBeginQuery(GL_SAMPLES_PASSED, fragments_query_.id());
        frame.scene.draw();
        glEndQuery(GL_SAMPLES_PASSED);
      } else {
        glBindFramebuffer(GL_FRAMEBUFFER, peel_targets_[current].id());
        glBlendEquationi(0, GL_MAX);
        // Front, under: rgb += transmittance (dst alpha) * premultiplied; alpha *= 1 - a.
        glBlendEquationi(1, GL_FUNC_ADD);
        glBlendFuncSeparatei(1, GL_DST_ALPHA, GL_ONE, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
        // Back, over: rgb = a * c + (1 - a) * rgb; alpha (transmittance) *= 1 - a.
        glBlendEquationi(2, GL_FUNC_ADD);
        glBlendFuncSeparatei(2, GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
        glUseProgram(peel_[last_allowed ? 1 : 0].id());
        glBindTextureUnit(DUAL_PEELING_RANGE_UNIT, ranges_[previous].id());
        frame.scene.draw();
      }
      ++passes_;
      if (early_exit_ && !last_allowed && !range_left(current)) break;
    }
    restore_default_blending();
    {
      auto compose = frame.clock.stage("compose");
      frame.bind_target();
      glUseProgram(compose_.id());
      glBindTextureUnit(DUAL_PEELING_FRONT_UNIT, front_.id());
      glBindTextureUnit(DUAL_PEELING_BACK_UNIT, back_.id());
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }

  TechniqueCounters counters() const override {
    TechniqueCounters c = peeling_counters(uint64_t(width_) * uint64_t(height_) * kBytesPerPixel + kCounterBytes,
                                           passes_, max_passes_, early_exit_);
    // Read lazily, so no frame waits for them.
    GLuint fragments = 0, left_unpeeled = 0;
    if (passes_ > 0) glGetQueryObjectuiv(fragments_query_.id(), GL_QUERY_RESULT, &fragments);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(counter_.id(), 0, sizeof left_unpeeled, &left_unpeeled);
    c.fragments_stored = fragments >= left_unpeeled ? fragments - left_unpeeled : 0;
    c.fragments_dropped = left_unpeeled;
    return c;
  }

 private:
  // Whether any pixel's range (written by the last pass) still holds a
  // fragment. Waits for that pass: the price of early exit.
  bool range_left(int range) {
    glBindFramebuffer(GL_FRAMEBUFFER, no_attachments_.id());
    glDisable(GL_BLEND);
    glUseProgram(range_check_.id());
    glBindTextureUnit(DUAL_PEELING_RANGE_UNIT, ranges_[range].id());
    glBeginQuery(GL_ANY_SAMPLES_PASSED, any_range_query_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEndQuery(GL_ANY_SAMPLES_PASSED);
    glEnable(GL_BLEND);
    GLuint any = 0;
    glGetQueryObjectuiv(any_range_query_.id(), GL_QUERY_RESULT, &any);
    return any != 0;
  }

  int max_passes_;
  bool early_exit_;
  Program init_[2], peel_[2], range_check_, compose_;  // [1]: counting variants
  Buffer counter_;
  Query fragments_query_, any_range_query_;
  Texture ranges_[2], front_, back_;
  Framebuffer range_targets_[2], peel_targets_[2], no_attachments_;
  int width_ = 0, height_ = 0;
  uint64_t passes_ = 0;
};

}  // namespace

void register_technique_dual_depth_peeling(TechniqueRegistry& registry) {
  registry.add(describe_peeler(
      {.id = "dual_depth_peeling",
       .display_name = "Dual depth peeling",
       .paper = "Bavoil & Myers 2008, Order independent transparency with dual depth peeling (NVIDIA)",
       .quality_sweep = {{"max_passes", {"2", "3", "5", "9", "17", "33"}}}},
      {"most geometry passes per frame, the min-max pass included (2 layers per later pass); too few leave the "
       "middle layers out",
       "stop once no depth range is left (occlusion query on a full-screen check); false runs exactly max_passes "
       "passes",
       "order of fragments at bit-identical depth: triangle_id composites them by stable id like the reference (any "
       "submission order gives the same image; ceil(d/2) + 2 passes); submission composites a tie in one pass in "
       "submission order (faster, ceil(d/2) + 1 passes, but the image of coplanar geometry depends on the "
       "submission order)",
       "stops peeling when an occlusion query finds a pass empty (about half the depth complexity + 1 passes)"},
      96,  // bytes per pixel of tie_break=triangle_id, the larger variant
      make_dual_depth_peeling_by_triangle_id, make_peeler<DualDepthPeelingBySubmission>));
}

}  // namespace oit
