// kbuffer: the dual-pass k-buffer (Kubisch 2014; the basis of the bucketed
// k-buffer of murray2016 section 4). Pass 1 (fill) keeps the K nearest depth
// keys of every pixel, sorted, by atomicMin insertion; pass 2 (store)
// re-renders and writes each of those fragments' colour into the slot of
// its key; compose blends the slots front to back. Fragments beyond the K
// nearest are dropped (counted) or blended, unsorted, behind them (`tail`).
// Exact whenever K >= the depth complexity of every pixel.
#include <algorithm>
#include <cstddef>
#include <map>
#include <string>

#include "harness/toolkit/fragment_pool.h"
#include "harness/toolkit/list_length_pass.h"
#include "harness/toolkit/technique.h"
#include "harness/toolkit/passes.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"
#include "harness/gl/uniform_block.h"
#include "algorithms/kbuffer/bindings.h"
#include "shaders/pixel_slots.h"

namespace oit {
namespace {

constexpr GLuint kEmpty = 0xffffffffu;

// Per slot, slot_layout=full: 4 (depth key) + 4 (owner triangle id) + 16
// (RGBA32F colour); slot_layout=paper: 4 (depth key) + 4 (RGBA8 colour).
enum class SlotLayout { full, paper };
const Choices<SlotLayout> kSlotLayouts{{SlotLayout::full, "full"}, {SlotLayout::paper, "paper"}};
constexpr uint64_t kKeyBytes = 4, kOwnerBytes = 4;
uint64_t color_bytes(SlotLayout layout) { return layout == SlotLayout::paper ? 4 : 16; }
uint64_t slot_bytes(SlotLayout layout) {
  return layout == SlotLayout::paper ? kKeyBytes + color_bytes(layout) : kKeyBytes + kOwnerBytes + color_bytes(layout);
}
constexpr int kMaxK = 64;  // the parameter's maximum: the worst-case constant k=auto is compared with
// Per pixel when tail=blend: RGBA16F accumulation + R16F revealage.
constexpr uint64_t kTailBytesPerPixel = 8 + 2;
constexpr uint64_t kCounterBytes = 8;
constexpr GLuint kZeroCounters[2] = {0, 0};  // stored, dropped: 0 until the first frame

// Fragments beyond the k nearest: dropped (counted) or blended unsorted behind them.
enum class Tail { drop, blend };
const Choices<Tail> kTails{{Tail::drop, "drop"}, {Tail::blend, "blend"}};

class KBuffer final : public Technique {
 public:
  explicit KBuffer(const ParamSet& params)
      : slots_(params, kMaxK),
        tail_blend_(params.choice("tail", kTails) == Tail::blend),
        layout_(params.choice("slot_layout", kSlotLayouts)),
        fill_(build_geometry_program("algorithms/kbuffer/fill.frag")),
        store_(build_geometry_program("algorithms/kbuffer/store.frag", layout_defines())),
        counters_(make_buffer(kCounterBytes, kZeroCounters)),
        frame_params_(OIT_PIXEL_SLOTS_PARAMS_BLOCK) {
    if (!slots_.automatic()) compose_for(slots_.fixed());  // compile errors surface at construction
  }

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    if (slots_.automatic()) {
      // k=auto: the most slots per pixel that fit both the memory cap and
      // the device's largest storage block (the colour buffer is the biggest).
      slots_.resize(width, height, slot_bytes(layout_), color_bytes(layout_));
      // The slots are allocated by the first frame, once its count is known.
      keys_ = Buffer();
      owners_ = Buffer();
      colors_ = Buffer();
      allocated_k_ = 0;
    } else {
      allocate_slots(slots_.fixed());
    }

    // The fill pass (and store without a tail) writes no colour: an
    // attachment-less framebuffer of the right size rasterises it.
    no_attachments_ = make_attachmentless_framebuffer(width, height);
    if (tail_blend_) {
      tail_accumulation_ = make_texture_2d(GL_RGBA16F, width, height);
      tail_revealage_ = make_texture_2d(GL_R16F, width, height);
      tail_framebuffer_ = make_target_framebuffer({&tail_accumulation_, &tail_revealage_},
                                                  "kbuffer: tail framebuffer (RGBA16F + R16F)");
    }
  }

  void render(const Frame& frame) override {
    const int k = slots_.for_frame(frame);
    const Program& compose = compose_for(k);
    frame_params_.values = {.width = width_, .k = k};
    frame_params_.upload();
    {
      auto clear = frame.clock.stage("clear");
      if (k != allocated_k_) allocate_slots(k);  // k=auto: storage follows the view
      const GLuint empty = kEmpty;
      fill_buffer_u32(keys_, empty);
      // The claim word: the owner, or with slot_layout=paper the packed colour (0 = none).
      if (layout_ == SlotLayout::paper) fill_buffer_u32(colors_, 0);
      else fill_buffer_u32(owners_, empty);
      fill_buffer_u32(counters_, 0);
      if (tail_blend_) {
        const GLfloat transparent[4] = {0.0f, 0.0f, 0.0f, 0.0f}, revealed = 1.0f;
        glClearTexImage(tail_accumulation_.id(), 0, GL_RGBA, GL_FLOAT, transparent);
        glClearTexImage(tail_revealage_.id(), 0, GL_RED, GL_FLOAT, &revealed);
      }
    }
    bind_storage();
    {
      auto fill = frame.clock.stage("fill");
      draw_scene_pass(frame, fill_, no_attachments_);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    {
      // The tail, if any: weighted blended OIT with weight 1 (store.frag).
      auto store = frame.clock.stage("store");
      if (tail_blend_) draw_weighted_blended_scene_pass(frame, store_, tail_framebuffer_);
      else draw_scene_pass(frame, store_, no_attachments_);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    {
      auto stage = frame.clock.stage("compose");
      if (tail_blend_) {
        glBindTextureUnit(KBUFFER_TAIL_ACCUMULATION_UNIT, tail_accumulation_.id());
        glBindTextureUnit(KBUFFER_TAIL_REVEALAGE_UNIT, tail_revealage_.id());
      }
      draw_fullscreen_pass(frame, compose);
    }
  }

  TechniqueCounters counters() const override {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint counts[2] = {0, 0};  // stored, dropped
    glGetNamedBufferSubData(counters_.id(), 0, sizeof(counts), counts);
    TechniqueCounters c;
    c.bytes_allocated = bytes_for(allocated_k_) + slots_.bytes_allocated();
    c.fragments_stored = counts[0];
    c.fragments_dropped = counts[1];
    c.passes = 2 + slots_.passes();
    slots_.add_figures(c.extra, allocated_k_);
    if (slots_.automatic()) {
      // Against the worst-case constant k = 64 (the parameter's maximum).
      const uint64_t pixels = uint64_t(width_) * uint64_t(height_);
      c.work_saved = {{"bytes_not_allocated", double(bytes_for(kMaxK)) - double(c.bytes_allocated)},
                      {"slots_not_cleared", double(pixels * uint64_t(kMaxK - allocated_k_))}};
    }
    return c;
  }

 private:
  // Slot storage, tail targets and counters for k slots per pixel.
  uint64_t bytes_for(int k) const {
    const uint64_t pixels = uint64_t(width_) * uint64_t(height_);
    return pixels * uint64_t(k) * slot_bytes(layout_) + (tail_blend_ ? pixels * kTailBytesPerPixel : 0) + kCounterBytes;
  }

  // The compose program for k slots. Only compose depends on the define K
  // (the size of its local arrays, K >= u_k): a fixed k compiles K = k;
  // k=auto compiles K = the next power of two, so at most 7 programs serve
  // every view (README, "k=auto").
  const Program& compose_for(int k) {
    int capacity = k;
    if (slots_.automatic()) {
      capacity = 1;
      while (capacity < k) capacity *= 2;
    }
    auto it = composes_.find(capacity);
    if (it == composes_.end()) {
      ShaderDefines defines = layout_defines();
      defines.push_back({"K", std::to_string(capacity)});
      it = composes_.emplace(capacity, build_fullscreen_program("algorithms/kbuffer/compose.frag", defines)).first;
    }
    return it->second;
  }

  ShaderDefines layout_defines() const {
    ShaderDefines defines;
    if (tail_blend_) defines.push_back({"TAIL_BLEND", "1"});
    if (layout_ == SlotLayout::paper) defines.push_back({"PAPER_SLOTS", "1"});
    return defines;
  }

  void allocate_slots(int k) {
    const uint64_t slots = uint64_t(width_) * uint64_t(height_) * uint64_t(k);
    check_slots_fit("kbuffer", k, width_, height_, slots * color_bytes(layout_), "the colour buffer");
    keys_ = make_buffer(GLsizeiptr(slots * kKeyBytes));
    owners_ = layout_ == SlotLayout::paper ? Buffer() : make_buffer(GLsizeiptr(slots * kOwnerBytes));
    colors_ = make_buffer(GLsizeiptr(slots * color_bytes(layout_)));
    gl_check("allocating the k-buffer of " + std::to_string(width_) + "x" + std::to_string(height_) + "x" +
             std::to_string(k));
    allocated_k_ = k;
  }

  void bind_storage() const {
    bind_storage_buffers({{KBUFFER_KEYS_BINDING, &keys_},
                          {KBUFFER_OWNERS_BINDING, &owners_},
                          {KBUFFER_COLORS_BINDING, &colors_},
                          {KBUFFER_COUNTERS_BINDING, &counters_}});
  }

  SlotsPerPixel slots_;
  bool tail_blend_;
  SlotLayout layout_;
  Program fill_, store_;
  std::map<int, Program> composes_;  // by K
  Buffer counters_, keys_, owners_, colors_;
  UniformBlock<PixelSlotsParams> frame_params_;
  Texture tail_accumulation_, tail_revealage_;
  Framebuffer no_attachments_, tail_framebuffer_;
  int width_ = 0, height_ = 0;
  int allocated_k_ = 0;
};

}  // namespace

void register_technique_kbuffer(TechniqueRegistry& registry) {
  registry.add({
      .id = "kbuffer",
      .display_name = "Dual-pass k-buffer",
      .paper = "Kubisch 2014, Order independent transparency in OpenGL 4.x (GTC 2014); murray2016 section 4",
      .params = {ParamSpec::integer_or_auto("k", "16", 1, kMaxK,
                                            "slots per pixel: the K nearest fragments are sorted exactly; auto = "
                                            "the view's depth complexity, counted every frame (capped by "
                                            "auto_k_memory_mb)"),
                 kTails.spec("tail", Tail::drop,
                             "fragments beyond the K nearest: drop (counted) or blend unsorted behind them"),
                 kSlotLayouts.spec("slot_layout", SlotLayout::full,
                                   "per slot: key, owner triangle id, RGBA32F colour (full, 24 bytes: the reference "
                                   "within float rounding, ties by triangle id) or key and RGBA8 colour (paper: "
                                   "murray2016's 8 bytes, colours quantised, ties by packed colour)"),
                 ParamSpec::integer("auto_k_memory_mb", 1024, 1, 1 << 20,
                                    "k=auto only: most MiB of slot storage (24 bytes per slot, 8 with "
                                    "slot_layout=paper); k is capped to fit")},
      .stages = {"count", "clear", "fill", "store", "compose"},  // count: only with k=auto
      // k slots per pixel: exact where k covers the depth complexity; with
      // tail=drop every fragment beyond them is counted in fragments_dropped.
      .exactness = Exactness::exact_while_storage_covers,
      .quality_sweep = {{"k", {"1", "2", "4", "8", "16", "32"}}, {"tail", kTails.names()}},
      .adaptive_switches = {{"k_auto",
                             "sizes k from the view's depth complexity (a counting pass) instead of the worst-case "
                             "constant 64",
                             {{"k", "auto"}},
                             {{"k", "64"}}}},
      .create = make_technique<KBuffer>,
      .storage_need = [](const ParamSet& params, const FrameContent& content) {
        const uint64_t slots = content.pixels() * fragment_pool::slots_per_pixel(content, params, kMaxK);
        const uint64_t tail = params.choice("tail", kTails) == Tail::blend ? kTailBytesPerPixel : 0;
        const SlotLayout layout = params.choice("slot_layout", kSlotLayouts);
        return StorageNeed{slots * color_bytes(layout), slots * slot_bytes(layout) + content.pixels() * (tail + 4)};
      },
  });
}

}  // namespace oit
