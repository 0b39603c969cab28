// kbuffer: the dual-pass k-buffer (Kubisch 2014; the basis of the bucketed
// k-buffer of murray2016 section 4). Pass 1 (fill) keeps the K nearest depth
// keys of every pixel, sorted, by atomicMin insertion; pass 2 (store)
// re-renders and writes each of those fragments' colour into the slot of
// its key; compose blends the slots front to back. Fragments beyond the K
// nearest are dropped (counted) or blended, unsorted, behind them (`tail`).
// Exact whenever K >= the depth complexity of every pixel.
#include <algorithm>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>

#include "harness/core/fragment_pool.h"
#include "harness/core/list_length_pass.h"
#include "harness/core/technique.h"
#include "harness/core/passes.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"
#include "harness/gl/uniforms.h"
#include "algorithms/kbuffer/bindings.h"

namespace oit {
namespace {

constexpr GLuint kEmpty = 0xffffffffu;

// Per slot: 4 (depth key) + 4 (owner triangle id) + 16 (RGBA32F colour).
constexpr uint64_t kKeyBytes = 4, kOwnerBytes = 4, kColorBytes = 16;
constexpr uint64_t kSlotBytes = kKeyBytes + kOwnerBytes + kColorBytes;
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
      : auto_k_(params.is_auto("k")),
        k_parameter_(auto_k_ ? 0 : int(params.integer("k"))),
        memory_cap_bytes_(uint64_t(params.integer("auto_k_memory_mb")) << 20),
        tail_blend_(params.choice("tail", kTails) == Tail::blend),
        fill_(build_geometry_program("algorithms/kbuffer/fill.frag")),
        store_(build_geometry_program("algorithms/kbuffer/store.frag", tail_defines())),
        counters_(make_buffer(kCounterBytes, kZeroCounters)) {
    if (auto_k_) count_pass_.emplace();
    else compose_for(k_parameter_);  // compile errors surface at construction
  }

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    for (const Program* program : {&fill_, &store_}) set_uniform(program->id(), KBUFFER_WIDTH_LOCATION, width);
    for (const auto& [capacity, compose] : composes_) set_uniform(compose.id(), KBUFFER_WIDTH_LOCATION, width);
    if (auto_k_) {
      count_pass_->resize(width, height);
      k_cap_ = auto_k_cap();
      // The slots are allocated by the first frame, once its count is known.
      keys_ = Buffer();
      owners_ = Buffer();
      colors_ = Buffer();
      allocated_k_ = 0;
    } else {
      allocate_slots(k_parameter_);
    }

    // The fill pass (and store without a tail) writes no colour: an
    // attachment-less framebuffer of the right size rasterises it.
    no_attachments_ = make_attachmentless_framebuffer(width, height);
    if (tail_blend_) {
      tail_accumulation_ = make_texture_2d(GL_RGBA16F, width, height);
      tail_revealage_ = make_texture_2d(GL_R16F, width, height);
      tail_framebuffer_ = make_framebuffer();
      glNamedFramebufferTexture(tail_framebuffer_.id(), GL_COLOR_ATTACHMENT0, tail_accumulation_.id(), 0);
      glNamedFramebufferTexture(tail_framebuffer_.id(), GL_COLOR_ATTACHMENT1, tail_revealage_.id(), 0);
      const GLenum attachments[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
      glNamedFramebufferDrawBuffers(tail_framebuffer_.id(), 2, attachments);
      if (glCheckNamedFramebufferStatus(tail_framebuffer_.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw GlError("kbuffer: tail framebuffer (RGBA16F + R16F) is incomplete");
    }
  }

  void render(const Frame& frame) override {
    int k = k_parameter_;
    if (auto_k_) {
      auto count = frame.clock.stage("count");
      longest_list_ = count_pass_->longest_list(frame);
      k = std::clamp(int(std::min<uint32_t>(longest_list_, kMaxK)), 1, k_cap_);
    }
    const Program& compose = compose_for(k);
    for (GLuint program : {fill_.id(), store_.id(), compose.id()})
      set_uniform(program, KBUFFER_SLOTS_LOCATION, k);
    {
      auto clear = frame.clock.stage("clear");
      if (k != allocated_k_) allocate_slots(k);  // k=auto: storage follows the view
      const GLuint empty = kEmpty;
      fill_buffer_u32(keys_, empty);
      fill_buffer_u32(owners_, empty);
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
      glBindFramebuffer(GL_FRAMEBUFFER, no_attachments_.id());
      glViewport(0, 0, width_, height_);
      glUseProgram(fill_.id());
      frame.set_shared_uniforms(fill_.id());
      frame.scene.draw();
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    {
      auto store = frame.clock.stage("store");
      glBindFramebuffer(GL_FRAMEBUFFER, tail_blend_ ? tail_framebuffer_.id() : no_attachments_.id());
      glViewport(0, 0, width_, height_);
      if (tail_blend_) {
        glEnablei(GL_BLEND, 0);
        glEnablei(GL_BLEND, 1);
        glBlendFunci(0, GL_ONE, GL_ONE);
        glBlendFunci(1, GL_ZERO, GL_ONE_MINUS_SRC_COLOR);
      }
      glUseProgram(store_.id());
      frame.set_shared_uniforms(store_.id());
      frame.scene.draw();
      glDisable(GL_BLEND);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    {
      auto stage = frame.clock.stage("compose");
      frame.bind_target();
      if (tail_blend_) {
        glBindTextureUnit(KBUFFER_TAIL_ACCUMULATION_UNIT, tail_accumulation_.id());
        glBindTextureUnit(KBUFFER_TAIL_REVEALAGE_UNIT, tail_revealage_.id());
      }
      glUseProgram(compose.id());
      frame.set_shared_uniforms(compose.id());
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }

  TechniqueCounters counters() const override {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint counts[2] = {0, 0};  // stored, dropped
    glGetNamedBufferSubData(counters_.id(), 0, sizeof(counts), counts);
    TechniqueCounters c;
    c.bytes_allocated = bytes_for(allocated_k_) + (auto_k_ ? count_pass_->bytes_allocated() : 0);
    c.fragments_stored = counts[0];
    c.fragments_dropped = counts[1];
    c.passes = auto_k_ ? 3 : 2;
    c.extra = {{"k_used", double(allocated_k_), Combine::max}};
    if (auto_k_) {
      // k_capped = 1: the view needed more slots than the cap allows, so
      // fragments beyond k_used were dropped (or blended) as with a fixed k.
      c.extra.push_back({"longest_list", double(longest_list_), Combine::max});
      c.extra.push_back({"k_cap", double(k_cap_), Combine::max});
      c.extra.push_back({"k_capped", longest_list_ > uint32_t(k_cap_) ? 1.0 : 0.0, Combine::max});
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
    return pixels * uint64_t(k) * kSlotBytes + (tail_blend_ ? pixels * kTailBytesPerPixel : 0) + kCounterBytes;
  }

  // k=auto: the most slots per pixel that fit both the memory cap and the
  // device's largest storage block (the colour buffer is the biggest), at
  // least 1 and at most the parameter's maximum.
  int auto_k_cap() const {
    return slots_per_pixel_cap(width_, height_, memory_cap_bytes_, kSlotBytes, kColorBytes, kMaxK);
  }

  // The compose program for k slots. Only compose depends on the define K
  // (the size of its local arrays, K >= u_k): a fixed k compiles K = k;
  // k=auto compiles K = the next power of two, so at most 7 programs serve
  // every view (README, "k=auto").
  const Program& compose_for(int k) {
    int capacity = k;
    if (auto_k_) {
      capacity = 1;
      while (capacity < k) capacity *= 2;
    }
    auto it = composes_.find(capacity);
    if (it == composes_.end()) {
      ShaderDefines defines = tail_defines();
      defines.push_back({"K", std::to_string(capacity)});
      it = composes_.emplace(capacity, build_fullscreen_program("algorithms/kbuffer/compose.frag", defines)).first;
      set_uniform(it->second.id(), KBUFFER_WIDTH_LOCATION, width_);
    }
    return it->second;
  }

  ShaderDefines tail_defines() const {
    if (tail_blend_) return {{"TAIL_BLEND", "1"}};
    return {};
  }

  void allocate_slots(int k) {
    const uint64_t slots = uint64_t(width_) * uint64_t(height_) * uint64_t(k);
    check_fits(k, slots * kColorBytes);
    keys_ = make_buffer(GLsizeiptr(slots * kKeyBytes));
    owners_ = make_buffer(GLsizeiptr(slots * kOwnerBytes));
    colors_ = make_buffer(GLsizeiptr(slots * kColorBytes));
    gl_check("allocating the k-buffer of " + std::to_string(width_) + "x" + std::to_string(height_) + "x" +
             std::to_string(k));
    allocated_k_ = k;
  }

  void check_fits(int k, uint64_t largest_buffer_bytes) const {
    GLint64 max_block = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    if (max_block > 0 && largest_buffer_bytes > uint64_t(max_block)) {
      throw std::runtime_error("kbuffer: k=" + std::to_string(k) + " at " + std::to_string(width_) + "x" +
                               std::to_string(height_) + " needs a " + std::to_string(largest_buffer_bytes >> 20) +
                               " MiB colour buffer, more than the device's largest storage block (" +
                               std::to_string(max_block >> 20) + " MiB); lower k or the size");
    }
  }

  void bind_storage() const {
    bind_storage_buffers({{KBUFFER_KEYS_BINDING, &keys_},
                          {KBUFFER_OWNERS_BINDING, &owners_},
                          {KBUFFER_COLORS_BINDING, &colors_},
                          {KBUFFER_COUNTERS_BINDING, &counters_}});
  }

  bool auto_k_;
  int k_parameter_;  // 0 with k=auto
  uint64_t memory_cap_bytes_;
  bool tail_blend_;
  Program fill_, store_;
  std::map<int, Program> composes_;  // by K
  std::optional<ListLengthPass> count_pass_;  // k=auto only
  Buffer counters_, keys_, owners_, colors_;
  Texture tail_accumulation_, tail_revealage_;
  Framebuffer no_attachments_, tail_framebuffer_;
  int width_ = 0, height_ = 0;
  int allocated_k_ = 0, k_cap_ = kMaxK;
  uint32_t longest_list_ = 0;
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
                 ParamSpec::integer("auto_k_memory_mb", 1024, 1, 1 << 20,
                                    "k=auto only: most MiB of slot storage (24 bytes per slot); k is capped to fit")},
      .stages = {"count", "clear", "fill", "store", "compose"},  // count: only with k=auto
      .exactness = Exactness::exact,
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
        return StorageNeed{slots * kColorBytes, slots * kSlotBytes + content.pixels() * (tail + 4)};
      },
  });
}

}  // namespace oit
