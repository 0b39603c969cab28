// depth_peeling: front-to-back depth peeling (Everitt 2001). Each geometry
// pass peels the nearest layer behind the one peeled before it (comparing
// against the previous pass's per-pixel key in the fragment shader, then the
// hardware depth test keeps the nearest survivor); a full-screen pass blends
// that layer under the accumulation. With early_exit an occlusion query stops
// at the first pass that peels nothing, so depth complexity d costs d + 1
// geometry passes. Exact when max_passes > the depth complexity.
//
// This file is tie_break=submission: depth ties are peeled in submission
// order. tie_break=triangle_id (the default, by_triangle_id.cpp) peels them
// by stable triangle id, as the reference does.
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "algorithms/depth_peeling/by_triangle_id.h"
#include "harness/toolkit/passes.h"
#include "harness/toolkit/peeling.h"
#include "harness/toolkit/technique.h"
#include "harness/gl/check.h"
#include "harness/gl/pass_queries.h"
#include "harness/gl/shader_program.h"
#include "algorithms/depth_peeling/bindings.h"

namespace oit {
namespace {

// Per pixel: layer colour RGBA32F (16) + depth buffer DEPTH32F (4) + two
// RG32UI layer keys (2 x 8) + accumulation RGBA32F (16).
constexpr uint64_t kBytesPerPixel = 16 + 4 + 2 * 8 + 16;
constexpr uint64_t kCounterBytes = sizeof(GLuint);

// The view depths the peel pass orders exactly (peel.frag scales them by
// 2^-64 into gl_FragDepth: exact for [2^-62, 2^64)), with margin.
constexpr double kMinNearDepth = 0x1p-50, kMaxFarDepth = 0x1p60;

// View depths of the near and far planes of a GL projection (where clip z
// equals -w and +w).
void check_depth_range(const glm::mat4& m) {
  const double near_depth = double(m[3][2] + m[3][3]) / double(m[2][2] + m[2][3]);
  const double far_depth = double(m[3][2] - m[3][3]) / double(m[2][2] - m[2][3]);
  if (!(near_depth >= kMinNearDepth && far_depth <= kMaxFarDepth)) {
    throw std::runtime_error("depth_peeling: the camera's view depths [" + std::to_string(near_depth) + ", " +
                             std::to_string(far_depth) +
                             "] leave [2^-50, 2^60], where the peel pass orders fragments exactly (a near "
                             "plane at or behind the eye would merge layers)");
  }
}

class DepthPeelingBySubmission final : public Technique {
 public:
  DepthPeelingBySubmission(int max_passes, bool early_exit)
      : max_passes_(max_passes),
        early_exit_(early_exit),
        peel_(build_geometry_program("algorithms/depth_peeling/peel.frag", {{"COUNT_SURVIVORS", "0"}})),
        // The atomic counter slows a pass down even where it never runs (Mesa
        // llvmpipe), so only the capped last pass uses the counting variant.
        peel_counting_(build_geometry_program("algorithms/depth_peeling/peel.frag", {{"COUNT_SURVIVORS", "1"}})),
        blend_layer_(build_fullscreen_program("algorithms/depth_peeling/blend_layer.frag")),
        compose_(build_fullscreen_program("algorithms/depth_peeling/compose.frag")),
        counter_(make_buffer(kCounterBytes)),
        any_samples_(make_query(GL_ANY_SAMPLES_PASSED)) {}

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    layer_color_ = make_texture_2d(GL_RGBA32F, width, height);
    depth_ = make_texture_2d(GL_DEPTH_COMPONENT32F, width, height);
    accumulation_ = make_texture_2d(GL_RGBA32F, width, height);
    accumulation_target_ = make_target_framebuffer({&accumulation_}, "depth_peeling: the accumulation framebuffer");
    // Two key targets alternate: a pass writes one and reads the other.
    for (int i = 0; i < 2; ++i) {
      keys_[i] = make_texture_2d(GL_RG32UI, width, height);
      peel_targets_[i] =
          make_target_framebuffer({&layer_color_, &keys_[i]}, "depth_peeling: the peel framebuffer", &depth_);
    }
    gl_check("allocating depth peeling targets of " + std::to_string(width) + "x" + std::to_string(height));
  }

  void render(const Frame& frame) override {
    check_depth_range(frame.projection);
    passes_ = 0;
    blended_passes_ = 0;
    last_allowed_pass_blended_ = false;
    {
      auto clear = frame.clock.stage("clear");
      const GLfloat nothing_accumulated[4] = {0.0f, 0.0f, 0.0f, 1.0f};  // rgb, transmittance
      glClearNamedFramebufferfv(accumulation_target_.id(), GL_COLOR, 0, nothing_accumulated);
      // What pass 1 reads: "peeled so far" ends at -infinity, i.e. nothing.
      const GLuint nothing_peeled_yet[4] = {float_bits(-std::numeric_limits<float>::infinity()), 0, 0, 0};
      glClearNamedFramebufferuiv(peel_targets_[0].id(), GL_COLOR, 1, nothing_peeled_yet);
      fill_buffer_u32(counter_, 0);
    }
    // Where a pass finds nothing its key stays +infinity: every later pass discards everything there.
    const GLuint nothing_here[4] = {float_bits(std::numeric_limits<float>::infinity()), 0, 0, 0};
    const GLfloat farthest = 1.0f;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DEPTH_PEELING_COUNTER_BINDING, counter_.id());
    for (const Program* program : {&peel_, &peel_counting_, &blend_layer_, &compose_})
      frame.set_shared_uniforms(program->id());
    for (int pass = 1; pass <= max_passes_; ++pass) {
      auto peel = frame.clock.stage("peel");
      const int current = pass % 2, previous = 1 - current;
      const Framebuffer& target = peel_targets_[current];
      glClearNamedFramebufferuiv(target.id(), GL_COLOR, 1, nothing_here);
      glClearNamedFramebufferfv(target.id(), GL_DEPTH, 0, &farthest);
      glBindFramebuffer(GL_FRAMEBUFFER, target.id());
      glViewport(0, 0, width_, height_);
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_LESS);
      glUseProgram(pass == max_passes_ ? peel_counting_.id() : peel_.id());
      glBindTextureUnit(DEPTH_PEELING_PREVIOUS_KEYS_UNIT, keys_[previous].id());
      if (early_exit_) glBeginQuery(GL_ANY_SAMPLES_PASSED, any_samples_.id());
      frame.scene.draw();
      ++passes_;
      glDisable(GL_DEPTH_TEST);
      if (early_exit_) {
        glEndQuery(GL_ANY_SAMPLES_PASSED);
        GLuint peeled_anything = 0;
        glGetQueryObjectuiv(any_samples_.id(), GL_QUERY_RESULT, &peeled_anything);  // waits for the pass
        if (!peeled_anything) break;
      }
      blend_layer_under_accumulation(current, pass);
    }
    {
      auto compose = frame.clock.stage("compose");
      frame.bind_target();
      glUseProgram(compose_.id());
      glBindTextureUnit(DEPTH_PEELING_ACCUMULATION_UNIT, accumulation_.id());
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }

  TechniqueCounters counters() const override {
    TechniqueCounters c = peeling_counters(uint64_t(width_) * uint64_t(height_) * kBytesPerPixel + kCounterBytes,
                                           passes_, max_passes_, early_exit_);
    // Read lazily, so no frame waits for them.
    const uint64_t peeled = blend_queries_.sum(0, size_t(blended_passes_));
    const uint64_t peeled_by_last_pass = blended_passes_ > 0 ? blend_queries_.result(size_t(blended_passes_ - 1)) : 0;
    c.fragments_stored = peeled;
    if (last_allowed_pass_blended_) {
      // What the capped last pass saw un-peeled but did not peel is never peeled.
      GLuint survivors = 0;
      glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
      glGetNamedBufferSubData(counter_.id(), 0, sizeof survivors, &survivors);
      c.fragments_dropped = survivors > peeled_by_last_pass ? survivors - peeled_by_last_pass : 0;
    }
    return c;
  }

 private:
  void blend_layer_under_accumulation(int current, int pass) {
    glBindFramebuffer(GL_FRAMEBUFFER, accumulation_target_.id());
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    // rgb: accumulated + transmittance (destination alpha) * premultiplied layer;
    // alpha: transmittance * (1 - layer alpha).
    glBlendFuncSeparate(GL_DST_ALPHA, GL_ONE, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(blend_layer_.id());
    glBindTextureUnit(DEPTH_PEELING_LAYER_COLOR_UNIT, layer_color_.id());
    glBindTextureUnit(DEPTH_PEELING_LAYER_KEYS_UNIT, keys_[current].id());
    glBeginQuery(GL_SAMPLES_PASSED, blend_queries_.at(size_t(pass - 1)).id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEndQuery(GL_SAMPLES_PASSED);
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);  // GL's default, which other techniques may assume
    blended_passes_ = pass;
    last_allowed_pass_blended_ = pass == max_passes_;
  }

  int max_passes_;
  bool early_exit_;
  Program peel_, peel_counting_, blend_layer_, compose_;
  Buffer counter_;
  Query any_samples_;
  PassSampleQueries blend_queries_;  // blend pass p at p - 1: fragments peeled
  Texture layer_color_, depth_, accumulation_, keys_[2];
  Framebuffer peel_targets_[2], accumulation_target_;
  int width_ = 0, height_ = 0;
  uint64_t passes_ = 0;
  int blended_passes_ = 0;
  bool last_allowed_pass_blended_ = false;
};

}  // namespace

void register_technique_depth_peeling(TechniqueRegistry& registry) {
  registry.add(describe_peeler(
      {.id = "depth_peeling",
       .display_name = "Depth peeling",
       .paper = "Everitt 2001, Interactive order-independent transparency (NVIDIA)",
       .quality_sweep = {{"max_passes", {"2", "4", "8", "16", "32", "64"}}}},
      {"most geometry passes per frame (layers peeled); fewer than the depth complexity leaves the farther layers "
       "out",
       "stop at the first pass that peels nothing (occlusion query); false runs exactly max_passes passes",
       "order of fragments at bit-identical depth: triangle_id peels them by stable id like the reference (any "
       "submission order gives the same image; d + 2 passes); submission peels them in submission order (faster, "
       "d + 1 passes, but the image of coplanar geometry depends on the submission order)",
       "stops peeling at the first pass that an occlusion query finds empty (depth complexity + 1 passes)"},
      56,  // bytes per pixel of tie_break=triangle_id, the larger variant
      make_depth_peeling_by_triangle_id, make_peeler<DepthPeelingBySubmission>));
}

}  // namespace oit
