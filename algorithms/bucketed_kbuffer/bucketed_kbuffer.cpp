// bucketed_kbuffer: the bucketed k-buffer of murray2016 with screen-space
// curvature and curvature/depth transfer functions. Stages: clear, fill (Z:
// K nearest keys by 32-bit atomicMin), sort (swap to shape-major and sort),
// bucket (per-pixel hash table; skipped by buckets=single, which auto takes on one object),
// store (second geometry pass: colour and normal), neighbors (links +
// curvature), stylize, compose (back to front).
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <cmath>
#include <cstddef>
#include <map>
#include <optional>
#include <stdexcept>

#include "algorithms/bucketed_kbuffer/accuracy.h"
#include "harness/toolkit/list_length_pass.h"
#include "harness/toolkit/technique.h"
#include "harness/toolkit/passes.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"
#include "harness/gl/uniform_block.h"
#include "algorithms/bucketed_kbuffer/choices.h"
#include "algorithms/bucketed_kbuffer/transfer_functions.h"
#include "algorithms/bucketed_kbuffer/bindings.h"

namespace oit {
namespace {

using bkb::BucketMode;
using bkb::BkbFrameParams;
static_assert(sizeof(BkbFrameParams) == 96 && offsetof(BkbFrameParams, curvature_scale) == 80);  // std140 = C++ here
constexpr int kMaxK = 64;  // the parameter's maximum: the worst case k=auto is compared with

// Every pass takes K as a compile-time define (local arrays, the hash
// table's size): one set of programs per k, built on first use (README,
// "k=auto").
struct KPrograms {
  Program fill, sort, bucket, store, compose, stylize;
  // Built when a frame needs them: the single-bucket sort and store, and the
  // neighbour search per Search (hashed buckets, brute force, single bucket)
  // and the merge search (neighbor_search=merge, any Search).
  Program sort_single_bucket, store_single_bucket, neighbors[3], neighbors_merge;
};

// One of KPrograms' programs built when a frame needs them: `build`s it the first time.
template <class Build>
GLuint built_on_first_use(Program& program, Build build) {
  if (!program) program = build();
  return program.id();
}

// How a frame finds a shape's fragments; the values are bkb_common.glsl's
// BKB_BUCKETS_* (the BUCKETS define of sort.frag, store.frag and neighbors.frag).
// single_bucket: buckets=single (auto on a one-object scene), where every list is one
// bucket, so no hash table is built (the bucket stage does not run) and the
// neighbour search visits whole lists without shape tests.
enum class Search { brute_force = 0, hashed = 1, single_bucket = 2 };

class BucketedKBuffer final : public Technique {
 public:
  explicit BucketedKBuffer(const ParamSet& params)
      : slots_(params, kMaxK),
        depth_bits_(params.choice("depth_bits", bkb::kDepthBits)),
        color_texels_(bkb::color_transfer_texels(params.choice("color_transfer", bkb::kColorTransfers),
                                                 params.path("color_transfer_file"))),
        opacity_texels_(bkb::opacity_transfer_texels(params.choice("opacity_transfer", bkb::kOpacityTransfers),
                                                     params.path("opacity_transfer_file"))),
        identity_(color_texels_.empty() && opacity_texels_.empty()),
        measure_(params.boolean("measure_accuracy")),
        merge_search_(params.choice("neighbor_search", bkb::kNeighborSearches) == bkb::NeighborSearch::merge),
        reverse_check_(params.boolean("reverse_check")),
        paper_slots_(params.choice("slot_layout", bkb::kSlotLayouts) == bkb::SlotLayout::paper),
        curvature_scale_(params.real("curvature_scale")),
        mode_(params.choice("buckets", bkb::kBucketModes)) {
    counter_ = make_buffer(sizeof(GLuint));
    if (!slots_.automatic()) programs_for(slots_.fixed());  // compile errors surface at construction
    if (!identity_) {
      if (!color_texels_.empty()) color_transfer_ = bkb::make_color_texture(color_texels_);
      if (!opacity_texels_.empty()) opacity_transfer_ = bkb::make_opacity_texture(opacity_texels_);
    }
    gl_check("bucketed_kbuffer: creating programs and transfer functions");
  }

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    no_attachments_ = make_attachmentless_framebuffer(width, height);
    if (slots_.automatic()) {
      // The largest single array: 16-byte truth records with measure_accuracy, else 4-byte words.
      slots_.resize(width, height, bytes_per_slot(), measure_ ? 16u : 4u);
      // The slots are allocated by the first frame, once its count is known.
      for (Buffer* b : {&z_, &buckets_, &colors_, &normals_, &features_, &links_, &expected_, &estimated_, &truth_})
        *b = Buffer();
      allocated_k_ = 0;
    } else {
      allocate_slots(slots_.fixed());
    }
  }

  // Per-slot arrays for k slots per pixel.
  void allocate_slots(int k) {
    const GLsizeiptr slots = GLsizeiptr(width_) * height_ * k;
    check_slots_fit("bucketed_kbuffer", k, width_, height_, uint64_t(slots) * 4, "each slot array");
    z_ = make_buffer(slots * 4);
    buckets_ = make_buffer(slots * 4);
    colors_ = make_buffer(slots * 4);
    normals_ = make_buffer(slots * 4);
    if (keeps_features()) features_ = make_buffer(slots * 4);
    if (measure_) {
      links_ = make_buffer(slots * 4);
      expected_ = make_buffer(slots * 4);
      estimated_ = make_buffer(slots * 4);
      truth_ = make_buffer(slots * 16);
    }
    gl_check("bucketed_kbuffer: allocating " + std::to_string(slots) + " slots");
    allocated_k_ = k;
  }

  // Z + B + colour + normal (+ features unless slot_layout=paper) (+ features,
  // links, expected, estimated, truth with measure_accuracy)
  uint64_t bytes_per_slot() const { return measure_ ? 48 : paper_slots_ ? 16 : 20; }
  // The features word (kappa, found mask): slot_layout=full, or measure_accuracy's counters.
  bool keeps_features() const { return !paper_slots_ || measure_; }

  void render(const Frame& frame) override {
    const int k = slots_.for_frame(frame);
    programs_ = &programs_for(k);
    programs_k_ = k;
    prepare_frame(frame);
    {
      auto clear = frame.clock.stage("clear");
      if (k != allocated_k_) allocate_slots(k);  // k=auto: storage follows the view
      const GLuint empty = 0xffffffffu;
      fill_buffer_u32(z_, empty);
      fill_buffer_u32(counter_, 0);
    }
    bind_storage();
    glBindFramebuffer(GL_FRAMEBUFFER, no_attachments_.id());
    glViewport(0, 0, width_, height_);
    geometry_pass(frame, "fill", programs_->fill.id());
    fullscreen_pass(frame, "sort", sort_program());
    if (search_ != Search::single_bucket) fullscreen_pass(frame, "bucket", programs_->bucket.id());
    geometry_pass(frame, "store", store_program());
    if (color_transfer_) glBindTextureUnit(BKB_COLOR_TRANSFER_UNIT, color_transfer_.id());
    if (opacity_transfer_) glBindTextureUnit(BKB_OPACITY_TRANSFER_UNIT, opacity_transfer_.id());
    fullscreen_pass(frame, "neighbors", neighbors_program());  // slot_layout=paper: stylizes too
    {
      // Both identity, or slot_layout=paper: the stage does no work.
      auto stylize = frame.clock.stage("stylize");
      if (programs_->stylize) run_fullscreen(frame, programs_->stylize.id());
    }
    auto compose = frame.clock.stage("compose");
    frame.bind_target();
    run_fullscreen(frame, programs_->compose.id());
  }

  TechniqueCounters counters() const override {
    TechniqueCounters c;
    c.passes = 2 + slots_.passes();
    const size_t k = size_t(allocated_k_), slots = size_t(width_) * size_t(height_) * k;
    c.bytes_allocated = bytes_for(allocated_k_) + slots_.bytes_allocated();
    if (slots_.automatic()) {
      // Against the worst-case constant k = 64 (the parameter's maximum).
      c.work_saved = {{"bytes_not_allocated", double(bytes_for(kMaxK)) - double(c.bytes_allocated)},
                      {"slots_not_cleared", double(size_t(width_) * size_t(height_) * size_t(kMaxK - allocated_k_))}};
    }
    // Against buckets=on: the last frame built no hash tables (one object).
    if (search_ == Search::single_bucket) c.work_saved.push_back({"bucket_passes_skipped", 1.0});
    if (slots == 0) return c;
    bkb::SlotReadback r;
    r.keys = read_uints(z_, slots);
    r.normals = read_uints(normals_, slots);
    if (features_) r.features = read_uints(features_, slots);
    if (measure_) r.links = read_uints(links_, slots);
    GLuint dropped = 0;
    glGetNamedBufferSubData(counter_.id(), 0, sizeof dropped, &dropped);
    const bkb::SlotStatistics s = bkb::slot_statistics(r, int(k), depth_bits_ == 24 ? 8 : 16);
    c.fragments_stored = s.stored;
    c.fragments_dropped = dropped + s.store_misses;
    c.extra = {{"bits_per_fragment", double(bytes_per_slot() * 8), Combine::max},
               // 1: hash-table buckets (buckets=on, or auto on several objects);
               // 0: brute force (off) or auto's single bucket on one object.
               {"buckets_used", search_ == Search::hashed ? 1.0 : 0.0, Combine::max},
               // 1 bucket per pixel (a single object): a bucket is the whole
               // list and buckets=on can only add the hash look-up's cost.
               {"buckets_per_pixel", s.covered_pixels ? double(s.buckets) / double(s.covered_pixels) : 0.0, Combine::mean},
               {"fragments_per_bucket", s.buckets ? double(s.kept) / double(s.buckets) : 0.0, Combine::mean},
               {"store_misses", double(s.store_misses)},
               {"depth_near", depth_near_},
               {"depth_far", depth_far_},
               {"depth_step", (depth_far_ - depth_near_) / double((1u << depth_bits_) - 2u)}};
    slots_.add_figures(c.extra, allocated_k_);
    if (features_) {  // slot_layout=paper keeps no found masks to count links from
      c.extra.push_back({"neighbor_links", double(s.links)});
      c.extra.push_back({"neighbor_links_per_fragment", s.stored ? double(s.links) / double(s.stored) : 0.0});
    }
    if (measure_) {
      c.extra.push_back({"link_checksum", double(s.link_checksum)});
      c.extra.push_back({"neighbor_mutual_links", double(bkb::mutual_links(r, width_, height_, int(k)))});
      r.truth = read_uints(truth_, slots * 4);
      const bkb::LinkAccuracy links = bkb::link_accuracy(r, width_, height_, int(k), bkb::kLinkFootprints);
      c.extra.push_back({"neighbor_precision", links.precision, Combine::mean});
      c.extra.push_back({"neighbor_recall", links.recall, Combine::mean});
      c.extra.push_back({"neighbor_correct_links", double(links.correct_links)});
      c.extra.push_back({"neighbor_true_neighbors", double(links.true_neighbors)});
      if (analytic_curvature_) {
        r.expected = read_floats(expected_, slots);
        r.estimated = read_floats(estimated_, slots);
        const bkb::CurvatureAccuracy a = bkb::curvature_accuracy(r, curvature_scale_);
        c.extra.push_back({"kappa_samples", double(a.samples)});
        c.extra.push_back({"kappa_mean_error", a.kappa_mean_error, Combine::mean});
        c.extra.push_back({"kappa_max_error", a.kappa_max_error, Combine::max});
        c.extra.push_back({"curvature_mean_rel_error", a.curvature_mean_relative_error, Combine::mean});
        c.extra.push_back({"curvature_max_rel_error", a.curvature_max_relative_error, Combine::max});
      }
    }
    return c;
  }

  // Per pixel, the front (nearest kept and stored) fragment's kappa and
  // found-neighbour count, from the Z, normal and feature buffers.
  std::vector<DiagnosticImage> diagnostic_images() const override {
    const size_t pixels = size_t(width_) * size_t(height_), k = size_t(allocated_k_);
    if (pixels == 0 || !features_) return {};  // slot_layout=paper keeps no kappa
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
  ShaderDefines defines(int k) const { return {{"K", std::to_string(k)}, {"DEPTH_BITS", std::to_string(depth_bits_)}}; }
  ShaderDefines store_defines(int k) const {
    ShaderDefines d = defines(k);
    d.push_back({"MEASURE_ACCURACY", measure_ ? "1" : "0"});
    return d;
  }
  ShaderDefines sort_defines(int k, Search search) const {
    ShaderDefines d = defines(k);
    d.push_back({"BUCKETS", std::to_string(int(search))});
    return d;
  }
  ShaderDefines search_defines(int k, Search search) const {
    ShaderDefines d = store_defines(k);
    d.push_back({"BUCKETS", std::to_string(int(search))});
    return d;
  }
  ShaderDefines neighbor_defines(int k, Search search) const {
    ShaderDefines d = search_defines(k, search);
    d.push_back({"SEARCH_MERGE", merge_search_ ? "1" : "0"});
    d.push_back({"REVERSE_CHECK", reverse_check_ ? "1" : "0"});
    d.push_back({"WRITE_FEATURES", keeps_features() ? "1" : "0"});
    const bool stylize_here = paper_slots_ && !identity_;
    d.push_back({"STYLIZE_HERE", stylize_here ? "1" : "0"});
    if (stylize_here) add_transfer_defines(d);
    return d;
  }
  void add_transfer_defines(ShaderDefines& d) const {
    d.push_back({"COLOR_TRANSFER", color_texels_.empty() ? "0" : "1"});
    d.push_back({"OPACITY_TRANSFER", opacity_texels_.empty() ? "0" : "1"});
  }

  // The programs for k slots per pixel; the neighbour programs are built by
  // neighbors_program() when a frame needs them.
  KPrograms& programs_for(int k) {
    auto it = programs_by_k_.find(k);
    if (it != programs_by_k_.end()) return it->second;
    KPrograms p;
    p.fill = build_geometry_program("algorithms/bucketed_kbuffer/fill.frag", defines(k));
    p.sort = build_fullscreen_program("algorithms/bucketed_kbuffer/sort.frag", sort_defines(k, Search::hashed));
    p.bucket = build_fullscreen_program("algorithms/bucketed_kbuffer/bucket.frag", defines(k));
    p.store = build_geometry_program("algorithms/bucketed_kbuffer/store.frag", search_defines(k, Search::hashed));
    p.compose = build_fullscreen_program("algorithms/bucketed_kbuffer/compose.frag", defines(k));
    if (!identity_ && !paper_slots_) {
      ShaderDefines d = defines(k);
      add_transfer_defines(d);
      p.stylize = build_fullscreen_program("algorithms/bucketed_kbuffer/stylize.frag", d);
    }
    return programs_by_k_.emplace(k, std::move(p)).first->second;
  }

  // Slot arrays, counter and transfer textures for k slots per pixel.
  uint64_t bytes_for(int k) const {
    return uint64_t(width_) * uint64_t(height_) * uint64_t(k) * bytes_per_slot() + sizeof(GLuint) +
           (color_transfer_ ? sizeof(float) * 4 * bkb::kColorTransferSize : 0) +
           (opacity_transfer_ ? sizeof(float) * bkb::kOpacityTransferSize * bkb::kOpacityTransferSize : 0);
  }

  // Per frame: the depth quantisation range, the bucket decision and the
  // parameter block (BkbFrameParams) and every program's shared uniforms.
  void prepare_frame(const Frame& frame) {
    const Scene& scene = frame.scene.scene();
    if (bounds_scene_ != frame.scene.serial()) {  // O(vertices): once per scene, not per frame
      bounds_ = scene.bounds();
      bounds_scene_ = frame.scene.serial();
    }
    analytic_curvature_ = scene.analytic_curvature;
    // buckets=auto is resolved before a run (register.cpp); a technique
    // built without the scene's facts (a test's renderer) decides it here,
    // the same way.
    const bool single = mode_ == BucketMode::single || (mode_ == BucketMode::automatic && scene.object_count <= 1);
    search_ = mode_ == BucketMode::off ? Search::brute_force : single ? Search::single_bucket : Search::hashed;
    // The scene's bounding sphere along the view axis bounds every fragment's
    // view depth; the view matrix may carry a uniform scale.
    const float scale = std::cbrt(std::abs(glm::determinant(glm::mat3(frame.view))));
    const float centre = -(frame.view * glm::vec4(bounds_.center, 1.0f)).z;
    const float radius = bounds_.radius * scale;
    depth_near_ = std::max(centre - radius, 0.0f);
    depth_far_ = std::max(centre + radius, depth_near_ + 1e-6f * std::max(1.0f, depth_near_));
    const KPrograms& p = *programs_;
    for (GLuint program : {p.fill.id(), sort_program(), p.bucket.id(), store_program(), neighbors_program(),
                           p.stylize.id(), p.compose.id()})
      if (program != 0) frame.set_shared_uniforms(program);
    frame_params_.values = {.inverse_projection = glm::inverse(frame.projection), .width = width_,
                            .height = height_, .depth_near = depth_near_, .depth_far = depth_far_,
                            .curvature_scale = float(curvature_scale_)};
    frame_params_.upload();
  }

  // The merge search reads whole sorted lists, so one program serves every
  // Search (built with the brute force's BUCKETS, which it ignores).
  GLuint neighbors_program() {
    const Search search = merge_search_ ? Search::brute_force : search_;
    Program& program = merge_search_ ? programs_->neighbors_merge : programs_->neighbors[int(search)];
    return built_on_first_use(program, [&] {
      return build_fullscreen_program("algorithms/bucketed_kbuffer/neighbors.frag",
                                      neighbor_defines(programs_k_, search));
    });
  }

  // buckets=single (auto on one object): the sort pass also records each list's
  // length, which replaces the hash table.
  GLuint sort_program() {
    if (search_ != Search::single_bucket) return programs_->sort.id();
    return built_on_first_use(programs_->sort_single_bucket, [&] {
      return build_fullscreen_program("algorithms/bucketed_kbuffer/sort.frag",
                                      sort_defines(programs_k_, Search::single_bucket));
    });
  }

  // buckets=off keeps the hashed store: the paper's brute force (Figure 10)
  // concerns only the neighbour query.
  GLuint store_program() {
    if (search_ != Search::single_bucket) return programs_->store.id();
    return built_on_first_use(programs_->store_single_bucket, [&] {
      return build_geometry_program("algorithms/bucketed_kbuffer/store.frag",
                                    search_defines(programs_k_, Search::single_bucket));
    });
  }

  void geometry_pass(const Frame& frame, const char* stage, GLuint program) {
    auto timed = frame.clock.stage(stage);
    glUseProgram(program);
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
    const Buffer* buffers[BKB_BUFFER_COUNT] = {&z_,       &buckets_, &colors_,   &normals_,    &features_,
                                               &counter_, &links_,   &expected_, &estimated_, &truth_};
    for (GLuint i = 0; i < BKB_BUFFER_COUNT; ++i)
      if (*buffers[i]) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BKB_Z_BINDING + i, buffers[i]->id());
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

  SlotsPerPixel slots_;
  int depth_bits_;
  std::vector<float> color_texels_, opacity_texels_;  // empty: identity (built-in choice, no file)
  bool identity_, measure_;
  bool merge_search_, reverse_check_, paper_slots_;
  double curvature_scale_;
  BucketMode mode_ = BucketMode::automatic;
  std::map<int, KPrograms> programs_by_k_;
  KPrograms* programs_ = nullptr;  // this frame's
  int programs_k_ = 0;
  int allocated_k_ = 0;
  Buffer z_, buckets_, colors_, normals_, features_, counter_, links_, expected_, estimated_, truth_;
  UniformBlock<BkbFrameParams> frame_params_{BKB_FRAME_PARAMS_BLOCK};
  Texture color_transfer_, opacity_transfer_;
  Framebuffer no_attachments_;
  int width_ = 0, height_ = 0;
  uint64_t bounds_scene_ = 0;  // SceneGpu::serial of bounds_, 0: none yet
  BoundingSphere bounds_;
  Search search_ = Search::hashed;  // this frame's
  bool analytic_curvature_ = false;
  float depth_near_ = 0.0f, depth_far_ = 1.0f;
};

}  // namespace

std::unique_ptr<Technique> make_bucketed_kbuffer(const ParamSet& params) {
  return std::make_unique<BucketedKBuffer>(params);
}

}  // namespace oit
