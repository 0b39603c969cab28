// stochastic_transparency: stochastic transparency (Enderton, Sintorn,
// Shirley & Luebke 2010). A multisampled depth pass lets each fragment
// cover a random alpha-sized subset of the pixel's samples (gl_SampleMask);
// a multisampled accumulation pass, depth-tested against it, adds each
// fragment's colour at the samples it is not hidden at, so the samples'
// average weights it by an unbiased estimate of its transmittance; compose
// applies the paper's alpha correction with the exact total coverage from
// a third, single-sampled pass. Order-independent, noisy; the noise falls
// with samples x passes.
#include <stdexcept>
#include <string>

#include "harness/toolkit/passes.h"
#include "harness/toolkit/technique.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"
#include "harness/gl/uniforms.h"
#include "algorithms/stochastic_transparency/bindings.h"

namespace oit {
namespace {


GLint get_integer(GLenum name) {
  GLint value = 0;
  glGetIntegerv(name, &value);
  return value;
}

// "" when the device can make multisampled depth and colour textures of
// `samples` samples, otherwise the reason (the runner makes it a skipped row).
std::string sample_count_support(int samples) {
  const GLint max_samples = get_integer(GL_MAX_SAMPLES);
  const GLint max_depth_samples = get_integer(GL_MAX_DEPTH_TEXTURE_SAMPLES);
  const GLint max_color_samples = get_integer(GL_MAX_COLOR_TEXTURE_SAMPLES);
  if (samples <= max_samples && samples <= max_depth_samples && samples <= max_color_samples) return "";
  return "stochastic_transparency: samples=" + std::to_string(samples) +
         " is more than the device supports (GL_MAX_SAMPLES " + std::to_string(max_samples) +
         ", GL_MAX_DEPTH_TEXTURE_SAMPLES " + std::to_string(max_depth_samples) + ", GL_MAX_COLOR_TEXTURE_SAMPLES " +
         std::to_string(max_color_samples) + ")";
}

// A multisampled 2D texture of exactly `samples` samples (GL may give more).
Texture make_multisample_texture(GLenum format, int samples, int width, int height) {
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &id);
  Texture texture(id);
  glTextureStorage2DMultisample(id, samples, format, width, height, GL_TRUE);
  gl_check("allocating a " + std::to_string(samples) + "-sample texture of " + std::to_string(width) + "x" +
           std::to_string(height));
  GLint actual = 0;
  glGetTextureLevelParameteriv(id, 0, GL_TEXTURE_SAMPLES, &actual);
  if (actual != samples)
    throw GlError("stochastic_transparency: asked for " + std::to_string(samples) + " samples, the device made " +
                  std::to_string(actual));
  return texture;
}

const Choices<int> kSampleCounts{{4, "4"}, {8, "8"}, {16, "16"}};  // MSAA samples of the depth pass

// Per sample D32F depth and RGBA32F accumulation, per pixel R32F total
// transmittance: what counters() reports and storage_need declares.
uint64_t storage_bytes(uint64_t pixels, int samples) { return pixels * (20u * uint64_t(samples) + 4u); }

class StochasticTransparency final : public Technique {
 public:
  explicit StochasticTransparency(const ParamSet& params)
      : samples_(params.choice("samples", kSampleCounts)),
        passes_(int(params.integer("passes"))),
        seed_(uint32_t(params.integer("seed"))),
        depth_(build_geometry_program("algorithms/stochastic_transparency/depth.frag", defines())),
        accumulate_(build_geometry_program("algorithms/stochastic_transparency/accumulate.frag")),
        total_(build_geometry_program("algorithms/stochastic_transparency/total.frag")),
        compose_(build_fullscreen_program("algorithms/stochastic_transparency/compose.frag", defines())) {
    if (std::string reason = sample_count_support(samples_); !reason.empty()) throw std::runtime_error(reason);
  }

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    stochastic_depth_ = make_multisample_texture(GL_DEPTH_COMPONENT32F, samples_, width, height);
    depth_framebuffer_ = make_target_framebuffer(
        {}, "stochastic_transparency: depth framebuffer (" + samples_text() + ")", &stochastic_depth_);

    accumulation_ = make_multisample_texture(GL_RGBA32F, samples_, width, height);
    accumulation_framebuffer_ = make_target_framebuffer(
        {&accumulation_}, "stochastic_transparency: accumulation framebuffer (" + samples_text() + ")",
        &stochastic_depth_);

    total_transmittance_ = make_texture_2d(GL_R32F, width, height);
    total_framebuffer_ = make_target_framebuffer({&total_transmittance_},
                                                 "stochastic_transparency: total transmittance framebuffer (R32F)");
  }

  void render(const Frame& frame) override {
    {
      auto clear = frame.clock.stage("clear");
      const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f}, one[4] = {1.0f, 1.0f, 1.0f, 1.0f};
      glClearNamedFramebufferfv(accumulation_framebuffer_.id(), GL_COLOR, 0, zero);
      glClearNamedFramebufferfv(total_framebuffer_.id(), GL_COLOR, 0, one);
    }
    glEnable(GL_MULTISAMPLE);
    for (int pass = 0; pass < passes_; ++pass) {
      {
        auto fill = frame.clock.stage("fill");
        const GLfloat far = 1.0f;
        glClearNamedFramebufferfv(depth_framebuffer_.id(), GL_DEPTH, 0, &far);
        set_uniform(depth_.id(), STOCHASTIC_TRANSPARENCY_SEED_LOCATION, seed_ + uint32_t(pass) * 0x9e3779b9u);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        draw_scene_pass(frame, depth_, depth_framebuffer_);
      }
      {
        auto store = frame.clock.stage("store");
        glDepthFunc(GL_LEQUAL);
        glDepthMask(GL_FALSE);
        draw_additive_scene_pass(frame, accumulate_, accumulation_framebuffer_);
        glDisable(GL_DEPTH_TEST);
        glDepthMask(GL_TRUE);
      }
    }
    {
      // The alpha correction's exact coverage: one more pass, not per seed.
      auto store = frame.clock.stage("store");
      glEnable(GL_BLEND);
      glBlendFunc(GL_ZERO, GL_ONE_MINUS_SRC_COLOR);
      draw_scene_pass(frame, total_, total_framebuffer_);
      glDisable(GL_BLEND);
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    {
      auto compose = frame.clock.stage("compose");
      glBindTextureUnit(STOCHASTIC_TRANSPARENCY_ACCUMULATION_UNIT, accumulation_.id());
      glBindTextureUnit(STOCHASTIC_TRANSPARENCY_TOTAL_TRANSMITTANCE_UNIT, total_transmittance_.id());
      draw_fullscreen_pass(frame, compose_);
    }
  }

  TechniqueCounters counters() const override {
    TechniqueCounters c;
    c.bytes_allocated = storage_bytes(uint64_t(width_) * uint64_t(height_), samples_);
    c.passes = 2 * uint64_t(passes_) + 1;
    c.extra = {{"effective_samples", double(samples_ * passes_)}};
    return c;
  }

 private:
  ShaderDefines defines() const { return {{"SAMPLES", std::to_string(samples_)}}; }

  std::string samples_text() const { return std::to_string(samples_) + " samples"; }

  int samples_, passes_;
  uint32_t seed_;
  Program depth_, accumulate_, total_, compose_;
  Texture stochastic_depth_, accumulation_, total_transmittance_;
  Framebuffer depth_framebuffer_, accumulation_framebuffer_, total_framebuffer_;
  int width_ = 0, height_ = 0;
};

}  // namespace

void register_technique_stochastic_transparency(TechniqueRegistry& registry) {
  registry.add({
      .id = "stochastic_transparency",
      .display_name = "Stochastic transparency",
      .paper = "Enderton, Sintorn, Shirley & Luebke 2010, Stochastic Transparency, I3D 2010",
      .params = {kSampleCounts.spec("samples", 4,
                                    "MSAA samples per pixel of the stochastic depth pass (a count the device lacks "
                                    "is a skipped run)"),
                 ParamSpec::integer("passes", 1, 1, 64,
                                    "depth + accumulation pass pairs with different seeds, averaged: samples x "
                                    "passes effective samples"),
                 ParamSpec::integer("seed", 1, 0, 0xffffffffLL, "seed of the per-fragment coverage masks")},
      .stages = {"clear", "fill", "store", "compose"},
      .quality_sweep = {{"samples", kSampleCounts.names()}, {"passes", {"1", "2", "4", "8"}}},
      .extra_support_check = [](const ParamSet& params, const SceneFacts&, const DeviceProfile&) {
        return sample_count_support(params.choice("samples", kSampleCounts));
      },
      .create = make_technique<StochasticTransparency>,
      // Textures only (no storage block): the budget, not the largest buffer, tiles it. The
      // coverage masks hash the image pixel (oit_image_pixel), so a tile draws the same samples.
      .storage_need = [](const ParamSet& params, const FrameContent& content) {
        return StorageNeed{0, storage_bytes(content.pixels(), params.choice("samples", kSampleCounts))};
      },
  });
}

}  // namespace oit
