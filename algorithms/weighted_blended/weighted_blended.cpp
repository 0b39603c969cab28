// weighted_blended: weighted blended order-independent transparency
// (McGuire & Bavoil 2013, JCGT 2(2)). One geometry pass accumulates a
// depth-weighted sum of premultiplied colours and the product of (1 - alpha)
// with commutative blending; compose divides out the weights. No sorting,
// no per-fragment storage: approximate, but independent of submission order.
#include <glm/glm.hpp>

#include <stdexcept>
#include <string>

#include "harness/core/technique.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"
#include "harness/gl/uniforms.h"
#include "algorithms/weighted_blended/bindings.h"

namespace oit {
namespace {


// View depths of the near and far planes of a GL projection matrix
// (glm: m[column][row]); perspective when m[2][3] == -1, else orthographic.
glm::vec2 near_far_of(const glm::mat4& p) {
  if (p[2][3] != 0.0f) return {p[3][2] / (p[2][2] - 1.0f), p[3][2] / (p[2][2] + 1.0f)};
  return {(p[3][2] + 1.0f) / p[2][2], (p[3][2] - 1.0f) / p[2][2]};
}

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
    framebuffer_ = make_framebuffer();
    glNamedFramebufferTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT0, accumulation_.id(), 0);
    glNamedFramebufferTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT1, revealage_.id(), 0);
    const GLenum attachments[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(framebuffer_.id(), 2, attachments);
    if (glCheckNamedFramebufferStatus(framebuffer_.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw GlError(std::string("weighted_blended: accumulation framebuffer (") +
                    (half_ ? "RGBA16F + R16F" : "RGBA32F + R32F") + ") is incomplete");
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
      glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
      glViewport(0, 0, width_, height_);
      glEnablei(GL_BLEND, 0);
      glEnablei(GL_BLEND, 1);
      glBlendFunci(0, GL_ONE, GL_ONE);
      glBlendFunci(1, GL_ZERO, GL_ONE_MINUS_SRC_COLOR);
      glUseProgram(fill_.id());
      frame.set_shared_uniforms(fill_.id());
      const glm::vec2 near_far = near_far_of(frame.projection);
      set_uniform(fill_.id(), WEIGHTED_BLENDED_NEAR_FAR_LOCATION, near_far);
      frame.scene.draw();
      glDisable(GL_BLEND);
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    {
      auto compose = frame.clock.stage("compose");
      frame.bind_target();
      glBindTextureUnit(WEIGHTED_BLENDED_ACCUMULATION_UNIT, accumulation_.id());
      glBindTextureUnit(WEIGHTED_BLENDED_REVEALAGE_UNIT, revealage_.id());
      glUseProgram(compose_.id());
      frame.set_shared_uniforms(compose_.id());
      glDrawArrays(GL_TRIANGLES, 0, 3);
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
