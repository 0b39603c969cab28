// bucketed_kbuffer: the bucketed k-buffer of murray2016 with screen-space
// curvature and curvature/depth transfer functions. Stages: clear, fill (Z:
// K nearest keys by 32-bit atomicMin), sort (swap to shape-major and sort),
// bucket (per-pixel hash table), store (second geometry pass: colour and
// normal), neighbors (links + curvature), stylize, compose (back to front).
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <cmath>
#include <stdexcept>

#include "accuracy.h"
#include "core/technique.h"
#include "gl/check.h"
#include "gl/shader_program.h"
#include "transfer_functions.h"
#include "../../shaders/bindings.h"

namespace oit {
namespace {

constexpr GLuint kBinding = OIT_FIRST_TECHNIQUE_BINDING;  // + 0..9, see bkb_common.glsl
constexpr GLint kUniform = OIT_FIRST_TECHNIQUE_UNIFORM;   // + 0..5
enum class BucketMode { automatic, on, off };

class BucketedKBuffer final : public Technique {
 public:
  explicit BucketedKBuffer(const ParamSet& params)
      : k_(int(params.integer("k"))),
        depth_bits_(params.choice("depth_bits") == "24" ? 24 : 16),
        color_function_(bkb::color_transfer_from_name(params.choice("color_transfer"))),
        opacity_function_(bkb::opacity_transfer_from_name(params.choice("opacity_transfer"))),
        identity_(color_function_ == bkb::ColorTransfer::identity &&
                  opacity_function_ == bkb::OpacityTransfer::identity),
        measure_(params.boolean("measure_accuracy")),
        curvature_scale_(params.real("curvature_scale")) {
    const std::string& buckets = params.choice("buckets");
    mode_ = buckets == "on" ? BucketMode::on : buckets == "off" ? BucketMode::off : BucketMode::automatic;
    fill_ = build_geometry_program("algorithms/bucketed_kbuffer/fill.frag", defines());
    sort_ = build_fullscreen_program("algorithms/bucketed_kbuffer/sort.frag", defines());
    bucket_ = build_fullscreen_program("algorithms/bucketed_kbuffer/bucket.frag", defines());
    store_ = build_geometry_program("algorithms/bucketed_kbuffer/store.frag", store_defines());
    compose_ = build_fullscreen_program("algorithms/bucketed_kbuffer/compose.frag", defines());
    counter_ = make_buffer(sizeof(GLuint));
    if (!identity_) {
      ShaderDefines d = defines();
      d.push_back({"COLOR_TRANSFER", color_function_ == bkb::ColorTransfer::identity ? "0" : "1"});
      d.push_back({"OPACITY_TRANSFER", opacity_function_ == bkb::OpacityTransfer::identity ? "0" : "1"});
      stylize_ = build_fullscreen_program("algorithms/bucketed_kbuffer/stylize.frag", d);
      if (color_function_ != bkb::ColorTransfer::identity) color_transfer_ = bkb::make_color_texture(color_function_);
      if (opacity_function_ != bkb::OpacityTransfer::identity)
        opacity_transfer_ = bkb::make_opacity_texture(opacity_function_);
    }
    gl_check("bucketed_kbuffer: creating programs and transfer functions");
  }

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    const GLsizeiptr slots = GLsizeiptr(width) * height * k_;
    GLint64 max_block = 0;  // each per-slot array is one storage block
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    if (max_block > 0 && slots * 4 > max_block)
      throw std::runtime_error("bucketed_kbuffer: k=" + std::to_string(k_) + " at " + std::to_string(width) + "x" +
                               std::to_string(height) + " needs " + std::to_string((slots * 4) >> 20) +
                               " MiB per slot array, above the device's largest storage block (" +
                               std::to_string(max_block >> 20) + " MiB); lower k or the size");
    z_ = make_buffer(slots * 4);
    buckets_ = make_buffer(slots * 4);
    colors_ = make_buffer(slots * 4);
    normals_ = make_buffer(slots * 4);
    features_ = make_buffer(slots * 4);
    if (measure_) {
      links_ = make_buffer(slots * 4);
      expected_ = make_buffer(slots * 4);
      estimated_ = make_buffer(slots * 4);
      truth_ = make_buffer(slots * 16);
    }
    no_attachments_ = make_framebuffer();
    glNamedFramebufferParameteri(no_attachments_.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, width);
    glNamedFramebufferParameteri(no_attachments_.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, height);
    gl_check("bucketed_kbuffer: allocating " + std::to_string(slots) + " slots");
  }

  void render(const Frame& frame) override {
    prepare_frame(frame);
    {
      auto clear = frame.clock.stage("clear");
      const GLuint empty = 0xffffffffu, zero = 0u;
      glClearNamedBufferData(z_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &empty);
      glClearNamedBufferData(counter_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    }
    bind_storage();
    glBindFramebuffer(GL_FRAMEBUFFER, no_attachments_.id());
    glViewport(0, 0, width_, height_);
    geometry_pass(frame, "fill", fill_);
    fullscreen_pass(frame, "sort", sort_.id());
    fullscreen_pass(frame, "bucket", bucket_.id());
    geometry_pass(frame, "store", store_);
    fullscreen_pass(frame, "neighbors", neighbors_program());
    {
      // Both identity: colour and alpha stay as stored; the stage does no work.
      auto stylize = frame.clock.stage("stylize");
      if (!identity_) {
        if (color_transfer_) glBindTextureUnit(0, color_transfer_.id());
        if (opacity_transfer_) glBindTextureUnit(1, opacity_transfer_.id());
        run_fullscreen(frame, stylize_.id());
      }
    }
    auto compose = frame.clock.stage("compose");
    frame.bind_target();
    run_fullscreen(frame, compose_.id());
  }

  TechniqueCounters counters() const override {
    TechniqueCounters c;
    c.passes = 2;
    const size_t slots = size_t(width_) * size_t(height_) * size_t(k_);
    // Z + B + colour + normal + features (+ links, expected, estimated, truth)
    const uint64_t bytes_per_slot = measure_ ? 48 : 20;
    c.bytes_allocated = slots * bytes_per_slot + sizeof(GLuint) +
                        (color_transfer_ ? sizeof(float) * 4 * bkb::kColorTransferSize : 0) +
                        (opacity_transfer_ ? sizeof(float) * bkb::kOpacityTransferSize * bkb::kOpacityTransferSize : 0);
    if (slots == 0) return c;
    bkb::SlotReadback r;
    r.keys = read_uints(z_, slots);
    r.normals = read_uints(normals_, slots);
    r.features = read_uints(features_, slots);
    if (measure_) r.links = read_uints(links_, slots);
    GLuint dropped = 0;
    glGetNamedBufferSubData(counter_.id(), 0, sizeof dropped, &dropped);
    const bkb::SlotStatistics s = bkb::slot_statistics(r, k_, depth_bits_ == 24 ? 8 : 16);
    c.fragments_stored = s.stored;
    c.fragments_dropped = dropped + s.store_misses;
    c.extra = {{"bits_per_fragment", double(bytes_per_slot * 8)},
               {"buckets_used", buckets_used_ ? 1.0 : 0.0},
               // 1 bucket per pixel (a single object): a bucket is the whole
               // list and buckets=on can only add the hash look-up's cost.
               {"buckets_per_pixel", s.covered_pixels ? double(s.buckets) / double(s.covered_pixels) : 0.0},
               {"fragments_per_bucket", s.buckets ? double(s.kept) / double(s.buckets) : 0.0},
               {"neighbor_links", double(s.links)},
               {"neighbor_links_per_fragment", s.stored ? double(s.links) / double(s.stored) : 0.0},
               {"store_misses", double(s.store_misses)},
               {"depth_near", depth_near_},
               {"depth_far", depth_far_},
               {"depth_step", (depth_far_ - depth_near_) / double((1u << depth_bits_) - 2u)}};
    if (measure_) {
      c.extra.push_back({"link_checksum", double(s.link_checksum)});
      r.truth = read_uints(truth_, slots * 4);
      const bkb::LinkAccuracy links = bkb::link_accuracy(r, width_, height_, k_, bkb::kLinkFootprints);
      c.extra.push_back({"neighbor_precision", links.precision});
      c.extra.push_back({"neighbor_recall", links.recall});
      c.extra.push_back({"neighbor_correct_links", double(links.correct_links)});
      c.extra.push_back({"neighbor_true_neighbors", double(links.true_neighbors)});
      if (analytic_curvature_) {
        r.expected = read_floats(expected_, slots);
        r.estimated = read_floats(estimated_, slots);
        const bkb::CurvatureAccuracy a = bkb::curvature_accuracy(r, curvature_scale_);
        c.extra.push_back({"kappa_samples", double(a.samples)});
        c.extra.push_back({"kappa_mean_error", a.kappa_mean_error});
        c.extra.push_back({"kappa_max_error", a.kappa_max_error});
        c.extra.push_back({"curvature_mean_rel_error", a.curvature_mean_relative_error});
        c.extra.push_back({"curvature_max_rel_error", a.curvature_max_relative_error});
      }
    }
    return c;
  }

  // Per pixel, the front (nearest kept and stored) fragment's kappa and
  // found-neighbour count, from the Z, normal and feature buffers.
  std::vector<DiagnosticImage> diagnostic_images() const override {
    const size_t pixels = size_t(width_) * size_t(height_), k = size_t(k_);
    if (pixels == 0) return {};
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const std::vector<uint32_t> keys = read_uints(z_, pixels * k), normals = read_uints(normals_, pixels * k),
                                features = read_uints(features_, pixels * k);
    gl_check("bucketed_kbuffer: reading back the slots for the diagnostic images");
    const float none = std::numeric_limits<float>::quiet_NaN();
    DiagnosticImage kappa{"kappa",
                          "front fragment's kappa = tanh(curvature_scale * (k1 + k2)): -1 convex (or a missing "
                          "neighbour), 0 flat, +1 concave",
                          width_, height_, std::vector<float>(pixels, none), -1.0f, 1.0f};
    DiagnosticImage links{"neighbor_count", "neighbours found for the front fragment (0-4)", width_, height_,
                          std::vector<float>(pixels, none), 0.0f, 4.0f};
    const uint32_t depth_mask = (1u << (depth_bits_ == 24 ? 24u : 16u)) - 1u;  // after the sort: depth low bits
    for (size_t p = 0; p < pixels; ++p) {
      size_t front = SIZE_MAX;
      for (size_t i = p * k; i < (p + 1) * k; ++i) {
        if (keys[i] == bkb::kEmptyKey || normals[i] == 0u) continue;
        if (front == SIZE_MAX || (keys[i] & depth_mask) < (keys[front] & depth_mask)) front = i;
      }
      if (front == SIZE_MAX) continue;
      kappa.values[p] = glm::unpackHalf1x16(uint16_t(features[front] & 0xffffu));
      links.values[p] = float(std::popcount((features[front] >> 16) & 0xfu));
    }
    return {std::move(kappa), std::move(links)};
  }

 private:
  // Only the defines a shader uses, so that variants share Mesa's shader cache.
  ShaderDefines defines() const { return {{"K", std::to_string(k_)}, {"DEPTH_BITS", std::to_string(depth_bits_)}}; }
  ShaderDefines store_defines() const {
    ShaderDefines d = defines();
    d.push_back({"MEASURE_ACCURACY", measure_ ? "1" : "0"});
    return d;
  }
  ShaderDefines neighbors_defines(bool bucketed) const {
    ShaderDefines d = store_defines();
    d.push_back({"BUCKETED", bucketed ? "1" : "0"});
    return d;
  }

  // Per frame: the depth quantisation range, the bucket decision and the
  // uniforms of every program.
  void prepare_frame(const Frame& frame) {
    const Scene& scene = frame.scene.scene();
    if (bounds_scene_ != &scene) {  // O(vertices): once per scene, not per frame
      bounds_ = scene.bounds();
      bounds_scene_ = &scene;
    }
    analytic_curvature_ = scene.analytic_curvature;
    buckets_used_ = mode_ == BucketMode::on || (mode_ == BucketMode::automatic && scene.object_count > 1);
    // The scene's bounding sphere along the view axis bounds every fragment's
    // view depth; the view matrix may carry a uniform scale.
    const float scale = std::cbrt(std::abs(glm::determinant(glm::mat3(frame.view))));
    const float centre = -(frame.view * glm::vec4(bounds_.center, 1.0f)).z;
    const float radius = bounds_.radius * scale;
    depth_near_ = std::max(centre - radius, 0.0f);
    depth_far_ = std::max(centre + radius, depth_near_ + 1e-6f * std::max(1.0f, depth_near_));
    const glm::mat4 inverse_projection = glm::inverse(frame.projection);
    for (GLuint program : {fill_.id(), sort_.id(), bucket_.id(), store_.id(), neighbors_program(), stylize_.id(),
                           compose_.id()}) {
      if (program == 0) continue;
      frame.set_shared_uniforms(program);
      if (active(program, "u_width")) glProgramUniform1i(program, kUniform + 0, width_);
      if (active(program, "u_height")) glProgramUniform1i(program, kUniform + 1, height_);
      if (active(program, "u_depth_near")) glProgramUniform1f(program, kUniform + 2, depth_near_);
      if (active(program, "u_depth_far")) glProgramUniform1f(program, kUniform + 3, depth_far_);
      if (active(program, "u_inverse_projection"))
        glProgramUniformMatrix4fv(program, kUniform + 4, 1, GL_FALSE, &inverse_projection[0][0]);
      if (active(program, "u_curvature_scale")) glProgramUniform1f(program, kUniform + 5, float(curvature_scale_));
    }
  }

  static bool active(GLuint program, const char* name) {
    return glGetProgramResourceIndex(program, GL_UNIFORM, name) != GL_INVALID_INDEX;
  }

  GLuint neighbors_program() {
    Program& program = buckets_used_ ? neighbors_bucketed_ : neighbors_brute_force_;
    if (!program) {
      program = build_fullscreen_program("algorithms/bucketed_kbuffer/neighbors.frag",
                                         neighbors_defines(buckets_used_));
    }
    return program.id();
  }

  void geometry_pass(const Frame& frame, const char* stage, const Program& program) {
    auto timed = frame.clock.stage(stage);
    glUseProgram(program.id());
    frame.scene.draw();
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }

  void fullscreen_pass(const Frame& frame, const char* stage, GLuint program) {
    auto timed = frame.clock.stage(stage);
    run_fullscreen(frame, program);
  }

  void run_fullscreen(const Frame&, GLuint program) {
    glUseProgram(program);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }

  void bind_storage() const {
    const Buffer* buffers[] = {&z_,       &buckets_, &colors_,   &normals_,    &features_,
                               &counter_, &links_,   &expected_, &estimated_, &truth_};
    for (GLuint i = 0; i < 10; ++i)
      if (*buffers[i]) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBinding + i, buffers[i]->id());
  }

  static std::vector<uint32_t> read_uints(const Buffer& buffer, size_t count) {
    std::vector<uint32_t> values(count);
    glGetNamedBufferSubData(buffer.id(), 0, GLsizeiptr(count * 4), values.data());
    return values;
  }
  static std::vector<float> read_floats(const Buffer& buffer, size_t count) {
    std::vector<float> values(count);
    glGetNamedBufferSubData(buffer.id(), 0, GLsizeiptr(count * 4), values.data());
    return values;
  }

  int k_, depth_bits_;
  bkb::ColorTransfer color_function_;
  bkb::OpacityTransfer opacity_function_;
  bool identity_, measure_;
  double curvature_scale_;
  BucketMode mode_ = BucketMode::automatic;
  Program fill_, sort_, bucket_, store_, neighbors_bucketed_, neighbors_brute_force_, stylize_, compose_;
  Buffer z_, buckets_, colors_, normals_, features_, counter_, links_, expected_, estimated_, truth_;
  Texture color_transfer_, opacity_transfer_;
  Framebuffer no_attachments_;
  int width_ = 0, height_ = 0;
  const Scene* bounds_scene_ = nullptr;
  BoundingSphere bounds_;
  bool buckets_used_ = true, analytic_curvature_ = false;
  float depth_near_ = 0.0f, depth_far_ = 1.0f;
};

}  // namespace

std::unique_ptr<Technique> make_bucketed_kbuffer(const ParamSet& params) {
  return std::make_unique<BucketedKBuffer>(params);
}

}  // namespace oit
