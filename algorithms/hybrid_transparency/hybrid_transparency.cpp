// hybrid_transparency: hybrid transparency (Maule, Comba, Torchelsen &
// Bastos 2013). The k nearest fragments of each pixel (the core) are kept
// in a k-buffer and composed exactly, front to back; every fragment behind
// them (the tail) is accumulated order-independently as a weighted average
// and composed behind the core as one layer. Two geometry passes: fill keeps
// the k nearest depth keys, store writes the core colours and accumulates
// the tail. Exact (up to the RGBA8 core colours) when k >= the depth
// complexity; otherwise only the tail is approximate.
#include <string>

#include "harness/toolkit/fill_store_compose.h"
#include "harness/toolkit/list_length_pass.h"
#include "harness/toolkit/passes.h"
#include "harness/toolkit/technique.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"
#include "harness/gl/uniform_block.h"
#include "shaders/pixel_slots.h"
#include "algorithms/hybrid_transparency/bindings.h"

namespace oit {
namespace {

constexpr GLuint kEmpty = 0xffffffffu;

// Per core slot: 4 (depth key) + 4 (RGBA8 colour).
constexpr uint64_t kSlotBytes = 8;
// Per pixel for the tail: RGBA32F sum + R32F count.
constexpr uint64_t kTailBytesPerPixel = 16 + 4;
constexpr uint64_t kCounterBytes = 8;
constexpr GLuint kZeroCounters[2] = {0, 0};

// What counters() reports and storage_need declares: the core (two buffers
// of k 4-byte entries per pixel, the largest single buffers) and the tail.
uint64_t core_buffer_bytes(uint64_t pixels, int k) { return pixels * uint64_t(k) * 4u; }
uint64_t storage_bytes(uint64_t pixels, int k) {
  return pixels * (uint64_t(k) * kSlotBytes + kTailBytesPerPixel) + kCounterBytes;
}

class HybridTransparency final : public Technique {
 public:
  explicit HybridTransparency(const ParamSet& params)
      : k_(int(params.integer("k"))),
        fill_(build_geometry_program("algorithms/hybrid_transparency/fill.frag")),
        store_(build_geometry_program("algorithms/hybrid_transparency/store.frag")),
        compose_(build_fullscreen_program("algorithms/hybrid_transparency/compose.frag")),
        counters_(make_buffer(kCounterBytes, kZeroCounters)) {
    params_.values.k = k_;
  }

  void resize(int width, int height) override {
    params_.values.width = width;
    const uint64_t pixels = uint64_t(width) * uint64_t(height), core_bytes = core_buffer_bytes(pixels, k_);
    check_slots_fit("hybrid_transparency", k_, width, height, core_bytes, "each core buffer");
    keys_ = make_buffer(GLsizeiptr(core_bytes));
    colors_ = make_buffer(GLsizeiptr(core_bytes));
    gl_check("allocating the hybrid transparency core of " + std::to_string(width) + "x" + std::to_string(height) +
             "x" + std::to_string(k_));

    no_attachments_ = make_attachmentless_framebuffer(width, height);  // fill writes no colour
    tail_sum_ = make_texture_2d(GL_RGBA32F, width, height);
    tail_count_ = make_texture_2d(GL_R32F, width, height);
    tail_framebuffer_ =
        make_target_framebuffer({&tail_sum_, &tail_count_}, "hybrid_transparency: tail framebuffer (RGBA32F + R32F)");
    bytes_allocated_ = storage_bytes(pixels, k_);
  }

  void render(const Frame& frame) override {
    params_.upload();
    {
      auto clear = frame.clock.stage("clear");
      const GLuint empty = kEmpty;
      fill_buffer_u32(keys_, empty);
      fill_buffer_u32(colors_, 0);
      fill_buffer_u32(counters_, 0);
      const GLfloat transparent[4] = {0.0f, 0.0f, 0.0f, 0.0f};
      glClearTexImage(tail_sum_.id(), 0, GL_RGBA, GL_FLOAT, transparent);
      glClearTexImage(tail_count_.id(), 0, GL_RED, GL_FLOAT, transparent);
    }
    bind_storage_buffers({{HYBRID_TRANSPARENCY_KEYS_BINDING, &keys_},
                          {HYBRID_TRANSPARENCY_COLORS_BINDING, &colors_},
                          {HYBRID_TRANSPARENCY_COUNTERS_BINDING, &counters_}});
    draw_fill_store_compose(frame, {.fill = fill_,
                                    .fill_target = no_attachments_,
                                    .store = store_,
                                    .store_target = tail_framebuffer_,
                                    .compose = compose_,
                                    .compose_inputs = {{HYBRID_TRANSPARENCY_TAIL_SUM_UNIT, &tail_sum_},
                                                       {HYBRID_TRANSPARENCY_TAIL_COUNT_UNIT, &tail_count_}}});
  }

  TechniqueCounters counters() const override {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint counts[2] = {0, 0};  // stored, tied_to_tail
    glGetNamedBufferSubData(counters_.id(), 0, sizeof(counts), counts);
    TechniqueCounters c;
    c.bytes_allocated = bytes_allocated_;
    c.fragments_stored = counts[0];
    c.fragments_dropped = 0;  // the tail composes every fragment beyond the core
    c.passes = 2;
    c.extra = {{"tied_to_tail", double(counts[1])}};
    return c;
  }

 private:
  int k_;
  Program fill_, store_, compose_;
  UniformBlock<PixelSlotsParams> params_{OIT_PIXEL_SLOTS_PARAMS_BLOCK};
  Buffer counters_, keys_, colors_;
  Texture tail_sum_, tail_count_;
  Framebuffer no_attachments_, tail_framebuffer_;
  uint64_t bytes_allocated_ = 0;  // set where the storage is made
};

}  // namespace

void register_technique_hybrid_transparency(TechniqueRegistry& registry) {
  registry.add({
      .id = "hybrid_transparency",
      .display_name = "Hybrid transparency",
      .paper = "Maule, Comba, Torchelsen & Bastos 2013, Hybrid Transparency, I3D 2013",
      .params = {ParamSpec::integer("k", 4, 1, 64,
                                    "core layers per pixel: the k nearest fragments are composed exactly, the "
                                    "rest as one weighted-average tail behind them")},
      .stages = {"clear", "fill", "store", "compose"},
      .quality_sweep = {{"k", {"1", "2", "4", "8", "16"}}},
      .create = make_technique<HybridTransparency>,
      .storage_need = [](const ParamSet& params, const FrameContent& content) {
        const int k = int(params.integer("k"));
        return StorageNeed{core_buffer_bytes(content.pixels(), k), storage_bytes(content.pixels(), k)};
      },
  });
}

}  // namespace oit
