// weighted_blended: weighted blended order-independent transparency
// (McGuire & Bavoil 2013, JCGT 2(2)). One geometry pass accumulates a
// depth-weighted sum of premultiplied colours and the product of (1 - alpha)
// with commutative blending; compose divides out the weights. No sorting,
// no per-fragment storage: approximate, but independent of submission order.
#include <string>

#include "harness/toolkit/passes.h"
#include "harness/toolkit/technique.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"
#include "harness/gl/uniform_block.h"
#include "algorithms/weighted_blended/bindings.h"

namespace oit {
namespace {

// The paper's weight functions, by equation number (fill.frag's WEIGHT_EQUATION).
const Choices<int> kWeights{{7, "eq7"}, {8, "eq8"}, {9, "eq9"}, {10, "eq10"}};
// Storage of the accumulation target.
enum class Precision { single, half };
const Choices<Precision> kPrecisions{{Precision::single, "float"}, {Precision::half, "half"}};

class WeightedBlended final : public Technique {
 public:
  explicit WeightedBlended(const ParamSet& params)
      : half_(params.choice("precision", kPrecisions) == Precision::half),
        fill_(build_geometry_program("algorithms/weighted_blended/fill.frag",
                                     {{"WEIGHT_EQUATION", std::to_string(params.choice("weight", kWeights))}})),
        compose_(build_fullscreen_program("algorithms/weighted_blended/compose.frag")) {}

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    accumulation_ = make_texture_2d(half_ ? GL_RGBA16F : GL_RGBA32F, width, height);
    revealage_ = make_texture_2d(half_ ? GL_R16F : GL_R32F, width, height);
    framebuffer_ = make_target_framebuffer({&accumulation_, &revealage_},
                                           std::string("weighted_blended: accumulation framebuffer (") +
                                               (half_ ? "RGBA16F + R16F" : "RGBA32F + R32F") + ")");
  }

  void render(const Frame& frame) override {
    {
      auto clear = frame.clock.stage("clear");
      const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f}, one[4] = {1.0f, 1.0f, 1.0f, 1.0f};
      glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, 0, zero);
      glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, 1, one);
    }
    {
      auto fill = frame.clock.stage("fill");
      const glm::vec2 near_far = frame.near_far();
      params_.values.near_view_depth = near_far.x;
      params_.values.far_view_depth = near_far.y;
      params_.upload();
      draw_weighted_blended_scene_pass(frame, fill_, framebuffer_);
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    {
      auto compose = frame.clock.stage("compose");
      glBindTextureUnit(WEIGHTED_BLENDED_ACCUMULATION_UNIT, accumulation_.id());
      glBindTextureUnit(WEIGHTED_BLENDED_REVEALAGE_UNIT, revealage_.id());
      draw_fullscreen_pass(frame, compose_);
    }
  }

  TechniqueCounters counters() const override {
    TechniqueCounters c;
    // accumulation RGBA + revealage R per pixel, 16- or 32-bit floats.
    c.bytes_allocated = uint64_t(width_) * uint64_t(height_) * (half_ ? 8 + 2 : 16 + 4);
    c.fragments_stored = 0;
    c.passes = 1;
    return c;
  }

 private:
  bool half_;
  Program fill_, compose_;
  UniformBlock<WeightedBlendedParams> params_{WEIGHTED_BLENDED_PARAMS_BLOCK};
  Texture accumulation_, revealage_;
  Framebuffer framebuffer_;
  int width_ = 0, height_ = 0;
};

}  // namespace

void register_technique_weighted_blended(TechniqueRegistry& registry) {
  registry.add({
      .id = "weighted_blended",
      .display_name = "Weighted blended OIT",
      .paper = "McGuire & Bavoil 2013, Weighted Blended Order-Independent Transparency, JCGT 2(2)",
      .params = {kWeights.spec("weight", 10,
                               "depth weight: the paper's eq. 7, 8, 9 (view depth rescaled from [near, far] to "
                               "[0.1, 500]) or 10 (window depth)"),
                 kPrecisions.spec("precision", Precision::single,
                                  "accumulation/revealage targets: RGBA32F + R32F, or the paper's RGBA16F + R16F")},
      .stages = {"clear", "fill", "compose"},
      .quality_sweep = {{"weight", kWeights.names()}},
      .create = make_technique<WeightedBlended>,
      // Two accumulation textures (precision=float's 20 bytes per pixel, the larger).
      .storage_need = [](const ParamSet&, const FrameContent& content) {
        return StorageNeed{0, content.pixels() * 20};
      },
  });
}

}  // namespace oit
