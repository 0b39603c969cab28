// adaptive_transparency: adaptive transparency (Salvi, Montgomery & Lefohn
// 2011). Pass 1 (fill) builds per pixel an adaptive visibility function of
// at most k nodes, compressing it by the smallest area change when a
// fragment adds one node too many; this read-modify-write runs in the
// pixel's ordered critical section (shaders/ordered_access.glsl: fragment
// shader interlock where the driver has it, else a bounded spin lock).
// Pass 2 (store) weights every fragment with the visibility at its depth;
// compose renormalises to the exact total coverage. Exact when k >= the
// depth complexity; otherwise it depends on the rasterisation order.
#include <string>

#include "harness/toolkit/fill_store_compose.h"
#include "harness/toolkit/passes.h"
#include "harness/toolkit/locked_pixel_counts.h"
#include "harness/toolkit/technique.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"
#include "harness/gl/uniform_block.h"
#include "shaders/pixel_slots.h"
#include "algorithms/adaptive_transparency/bindings.h"

namespace oit {
namespace {

// Per node: (depth, transmittance) as two 32-bit floats; k + 1 nodes per
// pixel (one spare for the insertion before compression).
constexpr uint64_t kNodeBytes = 8;
// Per pixel besides the nodes: the RGBA32F accumulation, and the node count
// (LockedPixelCounts::kBytesPerPixel).
constexpr uint64_t kAccumulationBytes = 16;

class AdaptiveTransparency final : public Technique {
 public:
  explicit AdaptiveTransparency(const ParamSet& params)
      : k_(int(params.integer("k"))),
        fill_(build_geometry_program("algorithms/adaptive_transparency/fill.frag")),
        store_(build_geometry_program("algorithms/adaptive_transparency/store.frag")),
        compose_(build_fullscreen_program("algorithms/adaptive_transparency/compose.frag")) {
    params_.values.k = k_;
  }

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    params_.values.width = width;
    const uint64_t pixels = uint64_t(width) * uint64_t(height);
    nodes_ = make_buffer(GLsizeiptr(pixels * uint64_t(k_ + 1) * kNodeBytes));
    counts_.resize(width, height);
    gl_check("allocating " + std::to_string(k_) + "-node visibility functions of " + std::to_string(width) + "x" +
             std::to_string(height));
    no_attachments_ = make_attachmentless_framebuffer(width, height);
    accumulation_ = make_texture_2d(GL_RGBA32F, width, height);
    accumulation_framebuffer_ =
        make_target_framebuffer({&accumulation_}, "adaptive_transparency: accumulation framebuffer (RGBA32F)");
  }

  void render(const Frame& frame) override {
    params_.upload();
    {
      auto clear = frame.clock.stage("clear");
      counts_.clear();
      const GLfloat transparent[4] = {0.0f, 0.0f, 0.0f, 0.0f};
      glClearNamedFramebufferfv(accumulation_framebuffer_.id(), GL_COLOR, 0, transparent);
    }
    bind_storage_buffers({{ADAPTIVE_TRANSPARENCY_NODES_BINDING, &nodes_}});
    counts_.bind(ADAPTIVE_TRANSPARENCY_COUNTS_BINDING, ADAPTIVE_TRANSPARENCY_LOCKS_BINDING);
    draw_fill_store_compose(frame, {.fill = fill_,
                                    .fill_target = no_attachments_,
                                    .store = store_,
                                    .store_target = accumulation_framebuffer_,
                                    .compose = compose_,
                                    .compose_inputs = {{ADAPTIVE_TRANSPARENCY_ACCUMULATION_UNIT, &accumulation_}}});
  }

  TechniqueCounters counters() const override {
    TechniqueCounters c;
    const uint64_t pixels = uint64_t(width_) * uint64_t(height_);
    c.bytes_allocated = pixels * (uint64_t(k_ + 1) * kNodeBytes + kAccumulationBytes);
    c.passes = 2;
    counts_.report(c, "node_removals");  // its drops: fragments missing from the visibility function
    return c;
  }

 private:
  int k_;
  Program fill_, store_, compose_;
  UniformBlock<PixelSlotsParams> params_{OIT_PIXEL_SLOTS_PARAMS_BLOCK};
  Buffer nodes_;
  LockedPixelCounts counts_;
  Texture accumulation_;
  Framebuffer no_attachments_, accumulation_framebuffer_;
  int width_ = 0, height_ = 0;
};

}  // namespace

void register_technique_adaptive_transparency(TechniqueRegistry& registry) {
  registry.add({
      .id = "adaptive_transparency",
      .display_name = "Adaptive transparency",
      .paper = "Salvi, Montgomery & Lefohn 2011, Adaptive Transparency, HPG 2011",
      .params = {ParamSpec::integer("k", 4, 1, 32,
                                    "nodes of each pixel's visibility function; one more is compressed away by "
                                    "the smallest area change")},
      .stages = {"clear", "fill", "store", "compose"},
      .quality_sweep = {{"k", {"1", "2", "4", "8", "16"}}},
      .create = make_technique<AdaptiveTransparency>,
      .storage_need = [](const ParamSet& params, const FrameContent& content) {
        const uint64_t nodes = content.pixels() * uint64_t(params.integer("k") + 1);
        return StorageNeed{nodes * kNodeBytes, nodes * kNodeBytes + content.pixels() * (kAccumulationBytes + LockedPixelCounts::kBytesPerPixel)};
      },
  });
}

}  // namespace oit
