// kbuffer: the dual-pass k-buffer (Kubisch 2014; the basis of the bucketed
// k-buffer of murray2016 section 4). Pass 1 (fill) keeps the K nearest depth
// keys of every pixel, sorted, by atomicMin insertion; pass 2 (store)
// re-renders and writes each of those fragments' colour into the slot of
// its key; compose blends the slots front to back. Fragments beyond the K
// nearest are dropped (counted) or blended, unsorted, behind them (`tail`).
// Exact whenever K >= the depth complexity of every pixel.
#include <stdexcept>
#include <string>

#include "core/technique.h"
#include "gl/check.h"
#include "gl/shader_program.h"
#include "../../shaders/bindings.h"

namespace oit {
namespace {

constexpr GLuint kKeysBinding = OIT_FIRST_TECHNIQUE_BINDING + 0;
constexpr GLuint kOwnersBinding = OIT_FIRST_TECHNIQUE_BINDING + 1;
constexpr GLuint kColorsBinding = OIT_FIRST_TECHNIQUE_BINDING + 2;
constexpr GLuint kCountersBinding = OIT_FIRST_TECHNIQUE_BINDING + 3;
constexpr GLuint kTailAccumulationUnit = OIT_FIRST_TECHNIQUE_BINDING + 0;
constexpr GLuint kTailRevealageUnit = OIT_FIRST_TECHNIQUE_BINDING + 1;
constexpr GLint kWidthLocation = OIT_FIRST_TECHNIQUE_UNIFORM + 0;
constexpr GLuint kEmpty = 0xffffffffu;

// Per slot: 4 (depth key) + 4 (owner triangle id) + 16 (RGBA32F colour).
constexpr uint64_t kKeyBytes = 4, kOwnerBytes = 4, kColorBytes = 16;
// Per pixel when tail=blend: RGBA16F accumulation + R16F revealage.
constexpr uint64_t kTailBytesPerPixel = 8 + 2;
constexpr uint64_t kCounterBytes = 8;
constexpr GLuint kZeroCounters[2] = {0, 0};  // stored, dropped: 0 until the first frame

class KBuffer final : public Technique {
 public:
  explicit KBuffer(const ParamSet& params)
      : k_(int(params.integer("k"))),
        tail_blend_(params.choice("tail") == "blend"),
        fill_(build_geometry_program("algorithms/kbuffer/fill.frag", {{"K", std::to_string(k_)}})),
        store_(build_geometry_program("algorithms/kbuffer/store.frag", tail_defines())),
        compose_(build_fullscreen_program("algorithms/kbuffer/compose.frag", tail_defines())),
        counters_(make_buffer(kCounterBytes, kZeroCounters)) {}

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    const uint64_t slots = uint64_t(width) * uint64_t(height) * uint64_t(k_);
    check_fits(slots * kColorBytes);
    keys_ = make_buffer(GLsizeiptr(slots * kKeyBytes));
    owners_ = make_buffer(GLsizeiptr(slots * kOwnerBytes));
    colors_ = make_buffer(GLsizeiptr(slots * kColorBytes));
    gl_check("allocating the k-buffer of " + std::to_string(width) + "x" + std::to_string(height) + "x" +
             std::to_string(k_));
    for (const Program* program : {&fill_, &store_, &compose_}) glProgramUniform1i(program->id(), kWidthLocation, width);

    // The fill pass (and store without a tail) writes no colour: an
    // attachment-less framebuffer of the right size rasterises it.
    no_attachments_ = make_framebuffer();
    glNamedFramebufferParameteri(no_attachments_.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, width);
    glNamedFramebufferParameteri(no_attachments_.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, height);
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
    {
      auto clear = frame.clock.stage("clear");
      const GLuint empty = kEmpty, zero = 0;
      glClearNamedBufferData(keys_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &empty);
      glClearNamedBufferData(owners_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &empty);
      glClearNamedBufferData(counters_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
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
      auto compose = frame.clock.stage("compose");
      frame.bind_target();
      if (tail_blend_) {
        glBindTextureUnit(kTailAccumulationUnit, tail_accumulation_.id());
        glBindTextureUnit(kTailRevealageUnit, tail_revealage_.id());
      }
      glUseProgram(compose_.id());
      frame.set_shared_uniforms(compose_.id());
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }

  TechniqueCounters counters() const override {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint counts[2] = {0, 0};  // stored, dropped
    glGetNamedBufferSubData(counters_.id(), 0, sizeof(counts), counts);
    const uint64_t pixels = uint64_t(width_) * uint64_t(height_);
    TechniqueCounters c;
    c.bytes_allocated = pixels * uint64_t(k_) * (kKeyBytes + kOwnerBytes + kColorBytes) +
                        (tail_blend_ ? pixels * kTailBytesPerPixel : 0) + kCounterBytes;
    c.fragments_stored = counts[0];
    c.fragments_dropped = counts[1];
    c.passes = 2;
    return c;
  }

 private:
  // The fill pass is the same for both tails (one shader-cache entry).
  ShaderDefines tail_defines() const {
    ShaderDefines d = {{"K", std::to_string(k_)}};
    if (tail_blend_) d.push_back({"TAIL_BLEND", "1"});
    return d;
  }

  void check_fits(uint64_t largest_buffer_bytes) const {
    GLint64 max_block = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    if (max_block > 0 && largest_buffer_bytes > uint64_t(max_block)) {
      throw std::runtime_error("kbuffer: k=" + std::to_string(k_) + " at " + std::to_string(width_) + "x" +
                               std::to_string(height_) + " needs a " + std::to_string(largest_buffer_bytes >> 20) +
                               " MiB colour buffer, more than the device's largest storage block (" +
                               std::to_string(max_block >> 20) + " MiB); lower k or the size");
    }
  }

  void bind_storage() const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kKeysBinding, keys_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOwnersBinding, owners_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kColorsBinding, colors_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCountersBinding, counters_.id());
  }

  int k_;
  bool tail_blend_;
  Program fill_, store_, compose_;
  Buffer counters_, keys_, owners_, colors_;
  Texture tail_accumulation_, tail_revealage_;
  Framebuffer no_attachments_, tail_framebuffer_;
  int width_ = 0, height_ = 0;
};

}  // namespace

void register_technique_kbuffer(TechniqueRegistry& registry) {
  TechniqueDescriptor d;
  d.id = "kbuffer";
  d.display_name = "Dual-pass k-buffer";
  d.paper = "Kubisch 2014, Order independent transparency in OpenGL 4.x (GTC 2014); murray2016 section 4";
  d.params = {ParamSpec::integer("k", 16, 1, 64, "slots per pixel: the K nearest fragments are sorted exactly"),
              ParamSpec::choice("tail", "drop", {"drop", "blend"},
                                "fragments beyond the K nearest: drop (counted) or blend unsorted behind them")};
  d.stages = {"clear", "fill", "store", "compose"};
  d.exactness = Exactness::exact;
  d.quality_sweep = {{"k", {"1", "2", "4", "8", "16", "32"}}, {"tail", {"drop", "blend"}}};
  d.create = [](const ParamSet& params) { return std::make_unique<KBuffer>(params); };
  registry.add(std::move(d));
}

}  // namespace oit
