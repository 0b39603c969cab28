// multi_layer_alpha_blending: multi-layer alpha blending (Salvi &
// Vaidyanathan 2014). One geometry pass keeps, per pixel, k layers sorted
// by depth and merges the two farthest with the over operator whenever a
// fragment makes it k + 1; compose blends the layers front to back. The
// per-pixel read-modify-write needs ordered access: fragment shader
// interlock where the driver has it, else a bounded per-pixel spin lock
// (shaders/ordered_access.glsl; README: why it cannot hang on llvmpipe).
// Exact when k >= the depth complexity or when fragments arrive front to
// back; otherwise the result depends on the rasterisation order.
#include <string>

#include "harness/toolkit/passes.h"
#include "harness/toolkit/locked_pixel_counts.h"
#include "harness/toolkit/technique.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"
#include "harness/gl/uniform_block.h"
#include "shaders/pixel_slots.h"
#include "algorithms/multi_layer_alpha_blending/bindings.h"

namespace oit {
namespace {

// Per layer: RGBA32F (premultiplied rgb, transmittance) + 32-bit float depth.
constexpr uint64_t kLayerBytes = 16 + 4;

class MultiLayerAlphaBlending final : public Technique {
 public:
  explicit MultiLayerAlphaBlending(const ParamSet& params)
      : k_(int(params.integer("k"))),
        fill_(build_geometry_program("algorithms/multi_layer_alpha_blending/fill.frag")),
        compose_(build_fullscreen_program("algorithms/multi_layer_alpha_blending/compose.frag")) {
    params_.values.k = k_;
  }

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    params_.values.width = width;
    const uint64_t pixels = uint64_t(width) * uint64_t(height);
    colors_ = make_buffer(GLsizeiptr(pixels * uint64_t(k_) * 16));
    depths_ = make_buffer(GLsizeiptr(pixels * uint64_t(k_) * 4));
    counts_.resize(width, height);
    gl_check("allocating " + std::to_string(k_) + " layers of " + std::to_string(width) + "x" +
             std::to_string(height));
    no_attachments_ = make_attachmentless_framebuffer(width, height);
  }

  void render(const Frame& frame) override {
    params_.upload();
    {
      auto clear = frame.clock.stage("clear");
      counts_.clear();
    }
    bind_storage_buffers({{MULTI_LAYER_ALPHA_BLENDING_COLORS_BINDING, &colors_},
                          {MULTI_LAYER_ALPHA_BLENDING_DEPTHS_BINDING, &depths_}});
    counts_.bind(MULTI_LAYER_ALPHA_BLENDING_COUNTS_BINDING, MULTI_LAYER_ALPHA_BLENDING_LOCKS_BINDING);
    {
      auto fill = frame.clock.stage("fill");
      draw_scene_pass(frame, fill_, no_attachments_);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    {
      auto compose = frame.clock.stage("compose");
      draw_fullscreen_pass(frame, compose_);
    }
  }

  TechniqueCounters counters() const override {
    TechniqueCounters c;
    c.bytes_allocated = uint64_t(width_) * uint64_t(height_) * uint64_t(k_) * kLayerBytes;
    c.passes = 1;
    counts_.report(c, "merges");
    return c;
  }

 private:
  int k_;
  Program fill_, compose_;
  UniformBlock<PixelSlotsParams> params_{OIT_PIXEL_SLOTS_PARAMS_BLOCK};
  Buffer colors_, depths_;
  LockedPixelCounts counts_;
  Framebuffer no_attachments_;
  int width_ = 0, height_ = 0;
};

}  // namespace

void register_technique_multi_layer_alpha_blending(TechniqueRegistry& registry) {
  registry.add({
      .id = "multi_layer_alpha_blending",
      .display_name = "Multi-layer alpha blending",
      .paper = "Salvi & Vaidyanathan 2014, Multi-layer Alpha Blending, I3D 2014",
      .params = {ParamSpec::integer("k", 4, 1, 32,
                                    "layers per pixel; a fragment that makes k + 1 merges the two farthest")},
      .stages = {"clear", "fill", "compose"},
      // Exact when k covers the depth complexity, but a fragment beyond k is
      // merged, not dropped, and fragments_dropped counts lock failures
      // only: a run that counted nothing may still be approximate, so it
      // cannot promise exact_while_storage_covers.
      .exactness = Exactness::approximate,
      .quality_sweep = {{"k", {"1", "2", "4", "8", "16"}}},
      .create = make_technique<MultiLayerAlphaBlending>,
      .storage_need = [](const ParamSet& params, const FrameContent& content) {
        const uint64_t layers = content.pixels() * uint64_t(params.integer("k"));
        // The largest buffer: the RGBA32F colours.
        return StorageNeed{layers * 16, layers * kLayerBytes + content.pixels() * LockedPixelCounts::kBytesPerPixel};
      },
  });
}

}  // namespace oit
