// moment_oit: moment-based order-independent transparency (Münstermann,
// Krumpen, Klein & Peters 2018). Pass 1 (fill) sums each pixel's absorbance
// and its power or trigonometric moments over depth with additive blending;
// pass 2 (store) re-renders every fragment and weights its colour with the
// transmittance reconstructed from those moments at its depth; compose
// renormalises the sum to the pixel's exact total opacity. No sorting, no
// per-fragment storage, independent of the submission order: approximate.
#include <glm/glm.hpp>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "harness/toolkit/passes.h"
#include "harness/toolkit/technique.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"
#include "harness/gl/uniform_block.h"
#include "algorithms/moment_oit/bindings.h"

namespace oit {
namespace {

constexpr double kPi = 3.14159265358979323846;

// One of the paper's six configurations: `moments` real numbers per pixel
// besides b0 (power: b1..b_moments; trigonometric: moments / 2 complex ones).
struct MomentConfig {
  bool trigonometric;
  int moments;
  bool operator==(const MomentConfig&) const = default;
};
const Choices<MomentConfig> kMomentConfigs{{{false, 4}, "power4"}, {{false, 6}, "power6"}, {{false, 8}, "power8"},
                                           {{true, 4}, "trig2"},   {{true, 6}, "trig3"},   {{true, 8}, "trig4"}};
// Storage of the moment and accumulation targets.
enum class Precision { single, half };
const Choices<Precision> kPrecisions{{Precision::single, "float"}, {Precision::half, "half"}};

// The paper's moment bias per configuration and storage (its Table 1 and
// supplementary): the smallest bias that kept its reconstructions stable.
double paper_moment_bias(const MomentConfig& config, bool half) {
  if (config.trigonometric) {
    switch (config.moments) {
      case 4: return half ? 4e-4 : 4e-7;
      case 6: return half ? 6.5e-4 : 8e-7;
      default: return half ? 8.5e-4 : 1.5e-6;
    }
  }
  switch (config.moments) {
    case 4: return half ? 6e-5 : 5e-7;
    case 6: return half ? 6e-4 : 5e-6;
    default: return half ? 2.5e-3 : 5e-5;
  }
}

// b0, the moments and the RGBA accumulation per pixel (6 moments use an RGBA
// and an RG target): what counters() reports and storage_need declares.
uint64_t storage_bytes(uint64_t pixels, const MomentConfig& config, bool half) {
  return pixels * (half ? 2u : 4u) * (1u + uint64_t(config.moments) + 4u);
}

class MomentOit final : public Technique {
 public:
  explicit MomentOit(const ParamSet& params)
      : config_(params.choice("moments", kMomentConfigs)),
        half_(params.choice("precision", kPrecisions) == Precision::half),
        moment_bias_(paper_moment_bias(config_, half_) * params.real("moment_bias_scale")),
        overestimation_(params.real("overestimation")),
        wrapping_zone_(params.real("wrapping_zone_degrees") * kPi / 180.0),
        fill_(build_geometry_program("algorithms/moment_oit/fill.frag", defines())),
        store_(build_geometry_program("algorithms/moment_oit/store.frag", defines())),
        compose_(build_fullscreen_program("algorithms/moment_oit/compose.frag")) {
    if (moment_bias_ >= 1.0)
      throw std::invalid_argument("moment_oit: moment_bias_scale=" + std::to_string(params.real("moment_bias_scale")) +
                                  " makes the moment bias " + std::to_string(moment_bias_) +
                                  " >= 1, which discards the moments entirely");
    params_.values.wrapping_zone = float(wrapping_zone_);
    params_.values.moment_bias = float(moment_bias_);
    params_.values.overestimation = float(overestimation_);
  }

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    zeroth_ = make_texture_2d(half_ ? GL_R16F : GL_R32F, width, height);
    moments_1_4_ = make_texture_2d(half_ ? GL_RGBA16F : GL_RGBA32F, width, height);
    if (config_.moments > 4) moments_5_8_ = make_texture_2d(high_moments_format(), width, height);
    accumulation_ = make_texture_2d(half_ ? GL_RGBA16F : GL_RGBA32F, width, height);

    std::vector<const Texture*> moment_targets = {&zeroth_, &moments_1_4_};
    if (config_.moments > 4) moment_targets.push_back(&moments_5_8_);
    moments_framebuffer_ =
        make_target_framebuffer(moment_targets, "moment_oit: moment framebuffer (" + precision_text() + ")");
    accumulation_framebuffer_ =
        make_target_framebuffer({&accumulation_}, "moment_oit: accumulation framebuffer (" + precision_text() + ")");
  }

  void render(const Frame& frame) override {
    upload_params(frame);
    {
      auto clear = frame.clock.stage("clear");
      const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
      for (GLint buffer = 0; buffer < (config_.moments > 4 ? 3 : 2); ++buffer)
        glClearNamedFramebufferfv(moments_framebuffer_.id(), GL_COLOR, buffer, zero);
      glClearNamedFramebufferfv(accumulation_framebuffer_.id(), GL_COLOR, 0, zero);
    }
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    {
      auto fill = frame.clock.stage("fill");
      draw_scene_pass(frame, fill_, moments_framebuffer_);
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    bind_moments();
    {
      auto store = frame.clock.stage("store");
      draw_scene_pass(frame, store_, accumulation_framebuffer_);
    }
    glDisable(GL_BLEND);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    {
      auto compose = frame.clock.stage("compose");
      glBindTextureUnit(MOMENT_OIT_ACCUMULATION_UNIT, accumulation_.id());
      draw_fullscreen_pass(frame, compose_);
    }
  }

  TechniqueCounters counters() const override {
    TechniqueCounters c;
    c.bytes_allocated = storage_bytes(uint64_t(width_) * uint64_t(height_), config_, half_);
    c.passes = 2;
    c.extra = {{"moment_bias", moment_bias_}};
    return c;
  }

 private:
  ShaderDefines defines() const {
    return {{"MOMENT_COUNT", std::to_string(config_.moments)}, {"TRIGONOMETRIC", config_.trigonometric ? "1" : "0"}};
  }

  GLenum high_moments_format() const {
    if (config_.moments == 6) return half_ ? GL_RG16F : GL_RG32F;
    return half_ ? GL_RGBA16F : GL_RGBA32F;
  }

  std::string precision_text() const { return half_ ? "16-bit float" : "32-bit float"; }

  // Uploads the parameters with this frame's depth warp. Depths are warped
  // onto [-1, 1] between the projection's planes:
  // logarithmically under perspective (the paper's warp: relative depth
  // differences matter equally near and far), linearly for an orthographic
  // projection, whose near plane may sit at or behind the eye.
  void upload_params(const Frame& frame) {
    const bool perspective = frame.projection[2][3] != 0.0f;
    glm::vec2 near_far = frame.near_far();
    if (perspective) near_far = glm::log(near_far);
    params_.values.warp_offset = near_far.x;
    params_.values.warp_scale = 1.0f / (near_far.y - near_far.x);
    params_.values.log_depth = perspective ? 1u : 0u;
    params_.upload();
  }

  void bind_moments() const {
    glBindTextureUnit(MOMENT_OIT_ZEROTH_UNIT, zeroth_.id());
    glBindTextureUnit(MOMENT_OIT_MOMENTS_1_4_UNIT, moments_1_4_.id());
    if (config_.moments > 4) glBindTextureUnit(MOMENT_OIT_MOMENTS_5_8_UNIT, moments_5_8_.id());
  }

  MomentConfig config_;
  bool half_;
  double moment_bias_, overestimation_, wrapping_zone_;
  Program fill_, store_, compose_;
  UniformBlock<MomentOitParams> params_{MOMENT_OIT_PARAMS_BLOCK};
  Texture zeroth_, moments_1_4_, moments_5_8_, accumulation_;
  Framebuffer moments_framebuffer_, accumulation_framebuffer_;
  int width_ = 0, height_ = 0;
};

}  // namespace

void register_technique_moment_oit(TechniqueRegistry& registry) {
  registry.add({
      .id = "moment_oit",
      .display_name = "Moment-based OIT",
      .paper = "Münstermann, Krumpen, Klein & Peters 2018, Moment-Based Order-Independent Transparency, PACMCGIT 1(1)",
      .params = {kMomentConfigs.spec("moments", {false, 6},
                                     "power moments (4, 6 or 8 of depth) or trigonometric moments (2, 3 or 4 of "
                                     "an angle)"),
                 kPrecisions.spec("precision", Precision::single,
                                  "moment and accumulation targets: 32-bit floats, or the paper's 16-bit (half) "
                                  "storage"),
                 ParamSpec::real("moment_bias_scale", 1.0, 0.0, 1e4,
                                 "multiplies the paper's moment bias of the configuration (e.g. 5e-6 for power6 "
                                 "at 32 bits); 0 = no bias"),
                 ParamSpec::real("overestimation", 0.25, 0.0, 1.0,
                                 "the paper's beta: 0 = lower bound of the absorbance in front, 1 = upper bound"),
                 ParamSpec::real("wrapping_zone_degrees", 18.0, 1.0, 180.0,
                                 "trigonometric moments: the angle between the far and the near end of the depth "
                                 "range (the paper's 0.1 pi)")},
      .stages = {"clear", "fill", "store", "compose"},
      .quality_sweep = {{"moments", {"power4", "trig2", "power6", "trig3", "power8", "trig4"}},
                        {"precision", {"half", "float"}}},
      .create = make_technique<MomentOit>,
      // Textures only (no storage block): the budget, not the largest buffer, tiles it.
      .storage_need = [](const ParamSet& params, const FrameContent& content) {
        return StorageNeed{0, storage_bytes(content.pixels(), params.choice("moments", kMomentConfigs),
                                            params.choice("precision", kPrecisions) == Precision::half)};
      },
  });
}

}  // namespace oit
