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

#include "core/technique.h"
#include "gl/check.h"
#include "gl/shader_capabilities.h"
#include "gl/shader_program.h"
#include "../../shaders/bindings.h"

namespace oit {
namespace {

constexpr GLuint kNodesBinding = OIT_FIRST_TECHNIQUE_BINDING + 0;
constexpr GLuint kCountsBinding = OIT_FIRST_TECHNIQUE_BINDING + 1;
constexpr GLuint kLocksBinding = OIT_FIRST_TECHNIQUE_BINDING + 2;
constexpr GLuint kAccumulationUnit = OIT_FIRST_TECHNIQUE_BINDING + 0;
constexpr GLint kWidthLocation = OIT_FIRST_TECHNIQUE_UNIFORM + 0;
constexpr GLint kNodesLocation = OIT_FIRST_TECHNIQUE_UNIFORM + 1;

// Per node: (depth, transmittance) as two 32-bit floats; k + 1 nodes per
// pixel (one spare for the insertion before compression).
constexpr uint64_t kNodeBytes = 8;
// Per pixel: node count, lock word, RGBA32F accumulation.
constexpr uint64_t kPixelBytes = 4 + 4 + 16;

class AdaptiveTransparency final : public Technique {
 public:
  explicit AdaptiveTransparency(const ParamSet& params)
      : k_(int(params.integer("k"))),
        fill_(build_geometry_program("algorithms/adaptive_transparency/fill.frag")),
        store_(build_geometry_program("algorithms/adaptive_transparency/store.frag")),
        compose_(build_fullscreen_program("algorithms/adaptive_transparency/compose.frag")) {
    for (GLuint program : {fill_.id(), store_.id(), compose_.id()}) glProgramUniform1i(program, kNodesLocation, k_);
  }

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    for (GLuint program : {fill_.id(), store_.id(), compose_.id()}) glProgramUniform1i(program, kWidthLocation, width);
    const uint64_t pixels = uint64_t(width) * uint64_t(height);
    nodes_ = make_buffer(GLsizeiptr(pixels * uint64_t(k_ + 1) * kNodeBytes));
    counts_ = make_buffer(GLsizeiptr(4 + pixels * 4));
    locks_ = make_buffer(GLsizeiptr(4 + pixels * 4));
    gl_check("allocating " + std::to_string(k_) + "-node visibility functions of " + std::to_string(width) + "x" +
             std::to_string(height));
    no_attachments_ = make_framebuffer();
    glNamedFramebufferParameteri(no_attachments_.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, width);
    glNamedFramebufferParameteri(no_attachments_.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, height);
    accumulation_ = make_texture_2d(GL_RGBA32F, width, height);
    accumulation_framebuffer_ = make_framebuffer();
    glNamedFramebufferTexture(accumulation_framebuffer_.id(), GL_COLOR_ATTACHMENT0, accumulation_.id(), 0);
    if (glCheckNamedFramebufferStatus(accumulation_framebuffer_.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw GlError("adaptive_transparency: accumulation framebuffer (RGBA32F) is incomplete");
  }

  void render(const Frame& frame) override {
    {
      auto clear = frame.clock.stage("clear");
      const GLuint zero = 0;
      glClearNamedBufferData(counts_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
      glClearNamedBufferData(locks_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
      const GLfloat transparent[4] = {0.0f, 0.0f, 0.0f, 0.0f};
      glClearNamedFramebufferfv(accumulation_framebuffer_.id(), GL_COLOR, 0, transparent);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kNodesBinding, nodes_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCountsBinding, counts_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLocksBinding, locks_.id());
    {
      auto fill = frame.clock.stage("fill");
      draw_geometry(frame, fill_, no_attachments_);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    {
      auto store = frame.clock.stage("store");
      glEnable(GL_BLEND);
      glBlendFunc(GL_ONE, GL_ONE);
      draw_geometry(frame, store_, accumulation_framebuffer_);
      glDisable(GL_BLEND);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    {
      auto compose = frame.clock.stage("compose");
      frame.bind_target();
      glBindTextureUnit(kAccumulationUnit, accumulation_.id());
      glUseProgram(compose_.id());
      frame.set_shared_uniforms(compose_.id());
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }

  TechniqueCounters counters() const override {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint removals = 0, lock_failures = 0;
    glGetNamedBufferSubData(counts_.id(), 0, 4, &removals);
    glGetNamedBufferSubData(locks_.id(), 0, 4, &lock_failures);
    TechniqueCounters c;
    const uint64_t pixels = uint64_t(width_) * uint64_t(height_);
    c.bytes_allocated = pixels * (uint64_t(k_ + 1) * kNodeBytes + kPixelBytes) + 8;
    c.fragments_dropped = lock_failures;  // fragments missing from the visibility function
    c.passes = 2;
    c.extra = {{"node_removals", double(removals)},
               {"lock_failures", double(lock_failures)},
               {"interlock", ordered_access_extension().empty() ? 0.0 : 1.0}};
    return c;
  }

 private:
  void draw_geometry(const Frame& frame, const Program& program, const Framebuffer& framebuffer) const {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
    glViewport(0, 0, width_, height_);
    glUseProgram(program.id());
    frame.set_shared_uniforms(program.id());
    frame.scene.draw();
  }

  int k_;
  Program fill_, store_, compose_;
  Buffer nodes_, counts_, locks_;
  Texture accumulation_;
  Framebuffer no_attachments_, accumulation_framebuffer_;
  int width_ = 0, height_ = 0;
};

}  // namespace

void register_technique_adaptive_transparency(TechniqueRegistry& registry) {
  TechniqueDescriptor d;
  d.id = "adaptive_transparency";
  d.display_name = "Adaptive transparency";
  d.paper = "Salvi, Montgomery & Lefohn 2011, Adaptive Transparency, HPG 2011";
  d.params = {ParamSpec::integer("k", 4, 1, 32,
                                 "nodes of each pixel's visibility function; one more is compressed away by the "
                                 "smallest area change")};
  d.stages = {"clear", "fill", "store", "compose"};
  d.exactness = Exactness::approximate;
  d.quality_sweep = {{"k", {"1", "2", "4", "8", "16"}}};
  d.create = [](const ParamSet& params) { return std::make_unique<AdaptiveTransparency>(params); };
  registry.add(std::move(d));
}

}  // namespace oit
