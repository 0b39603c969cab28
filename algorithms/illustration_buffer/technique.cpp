// illustration_buffer: per-pixel linked lists of rich fragment records
// (fill), sorted into contiguous per-pixel ranges (sort), linked to their
// geodesic neighbours in the 4 adjacent pixels (neighbors), transparency
// fields set and diffused along those links (stylize), then blended front
// to back (compose). See README.md for the mapping to the papers.
#include <algorithm>
#include <bit>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "algorithms/illustration_buffer/accuracy.h"
#include "algorithms/illustration_buffer/bindings.h"
#include "algorithms/illustration_buffer/settings.h"
#include "algorithms/illustration_buffer/triangle_table.h"
#include "harness/core/fragment_pool.h"
#include "harness/core/list_length_pass.h"
#include "harness/core/passes.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"
#include "harness/gl/uniforms.h"

namespace oit::illustration_buffer {
namespace {

constexpr GLsizeiptr kFragmentBytes = 48, kNextBytes = 4, kTruthBytes = 16, kFieldBytes = 16;
constexpr GLsizeiptr kDistanceBytes = 4;  // the sweeps' hop distances (sweep_distances.glsl)
// The sorted records, split over fragData2 (key, geometry) and fragData3 (colour, links).
constexpr GLsizeiptr kSearchBytes = 32, kShadeBytes = 32;
// The largest per-record buffer (fragData; it also holds both field ranges) bounds the pool.
constexpr GLsizeiptr kLargestRecordBytes = std::max({kFragmentBytes, kSearchBytes, kShadeBytes, 2 * kFieldBytes});
constexpr GLsizeiptr kCounterBytes = 20;  // produced, longest, dropped, truncated, allocated
// A worklist (worklist.glsl): indirect-dispatch arguments and count, then one entry per pixel.
constexpr GLsizeiptr kWorklistHeaderBytes = 16;
// The smallest sort array compiled (lists of up to 4, e.g. the torus's, with
// storage=linearized or arrays, where the dynamic sort is not offered).
constexpr uint32_t kSmallestArray = 4;
constexpr uint32_t kLargestSearchGroup = 4;  // triangle_search_program
// sort=auto takes the dynamic sort up to this longest list: faster there on
// llvmpipe (README, Sort variants), the array's ranks beyond.
constexpr uint32_t kLongestDynamicList = 4;
// Keeps both field ranges inside fragData for any storage-offset alignment up to 4 KiB.
constexpr uint64_t kSmallestPool = 256;
// Settings::arrays_where_even: per-pixel arrays only where their slots
// (pixels x longest list) hold at most this many times the fragments; more
// uneven lists (a few deep pixels) take the counting pass and exact ranges.
constexpr uint64_t kMostSlotsPerFragment = 4;

// u_width and u_height (ib_storage.glsl) are declared for every program and
// used by some: the compiler drops the others (uniforms.h).
void set_size(GLuint program, int width, int height) {
  if (uniform_active(program, "u_width")) set_uniform(program, IB_WIDTH_LOCATION, width);
  if (uniform_active(program, "u_height")) set_uniform(program, IB_HEIGHT_LOCATION, height);
}

uint64_t bytes_per_fragment(const Settings& s) {
  return uint64_t((s.ranged() ? 0 : kNextBytes) + kFragmentBytes + kSearchBytes + kShadeBytes +
                  (s.measure_accuracy ? kTruthBytes : 0) + (s.may_sweep() ? kDistanceBytes : 0));
}

// The steps of skip_converged (worklist.glsl); the sweeps need no tracking.
bool tracks_convergence(const Settings& s) {
  return s.diffused() && s.skip_converged && s.diffusion == Diffusion::steps;
}

// Per pixel: head and count; with storage=linearized the counting pass's
// R32F count, the fill's offset and its cursor, and an entry in the list of
// covered pixels (pixel_dispatch.glsl); with arrays the same but the count
// target (the offsets buffer holds the fill's counts); plus (when the diffusion
// skips converged fragments) a stamp, an entry in each of three worklists,
// an update count and a seed mark (stylize_seed_queue.comp).
uint64_t bytes_per_pixel(const Settings& s) {
  return 8 + (s.linearized() ? 16 : s.arrays() ? 12 : 0) + (tracks_convergence(s) ? 24 : 0);
}

// storage=linearized or arrays taking its slots by framebuffer fetch (fill, resolved on this device).
bool fetches_cursors(const Settings& s) { return s.ranged() && fills_by_framebuffer_fetch(s.fill); }

// Combinations that cannot work, named (the constructor throws them).
void check_combination(const Settings& s) {
  if (s.ranged() && s.sort == SortMethod::dynamic)
    throw std::invalid_argument(
        "illustration_buffer: sort=dynamic sorts the fill's linked lists and needs storage=linked (storage=linearized "
        "and arrays sort each pixel's contiguous range with sort=array or auto)");
  if (!s.ranged() && s.fill != SlotFill::automatic)
    throw std::invalid_argument("illustration_buffer: fill=atomic or fill=framebuffer_fetch chooses how "
                                "storage=linearized or arrays takes its slots; with storage=linked leave fill=auto");
  const bool sweep = s.diffused() && s.diffusion == Diffusion::sweep;
  if (sweep && s.adaptive_alpha)
    throw std::invalid_argument("illustration_buffer: diffusion=sweep leaves alpha as it starts, which eq. 8 would "
                                "diffuse with adaptive_alpha=true; use diffusion=steps or auto");
  if (sweep && !s.sweep_reaches_steps())
    throw std::invalid_argument(
        "illustration_buffer: diffusion=sweep gives the fixed point, which equals the steps' result only when "
        "`iterations` steps take beta and gamma from 1 to 0 (iterations + 1 >= 1 / lambda_beta, 1 / lambda_gamma); "
        "use diffusion=steps or auto");
  if (sweep && s.diffusion_tolerance > 0.0f)
    throw std::invalid_argument("illustration_buffer: diffusion_tolerance stops small moves of diffusion=steps; "
                                "diffusion=sweep is exact: leave the tolerance at 0 or use diffusion=steps");
}

// What the fill and the sort share: the storage (`arrays`: this frame's
// ranges are per-pixel arrays) and how the fill took its slots.
ShaderDefines storage_defines(const Settings& s, bool arrays) {
  ShaderDefines defines;
  if (s.ranged()) defines.push_back({"IB_RANGED", "1"});
  if (arrays) defines.push_back({"IB_ARRAYS", "1"});
  if (fetches_cursors(s)) defines.push_back({"IB_FETCH_CURSOR", "1"});
  return defines;
}

// The per-pixel passes' dispatch (pixel_dispatch.glsl): with
// storage=linearized or arrays over the covered pixels the host lists.
ShaderDefines per_pixel_defines(const Settings& s) {
  return s.ranged() ? ShaderDefines{{"IB_LISTED", "1"}} : ShaderDefines{};
}

ShaderDefines fill_defines(const Settings& s, bool flat, bool arrays) {
  ShaderDefines defines = storage_defines(s, arrays);
  if (flat) defines.push_back({"IB_FLAT_COLOR", "1"});
  if (s.measure_accuracy) defines.push_back({"IB_MEASURE", "1"});
  if (s.records_surface()) defines.push_back({"IB_SURFACE", "1"});
  if (s.modulation == Modulation::angle) defines.push_back({"IB_ANGLE", "1"});
  if (s.modulation == Modulation::normal_variation) defines.push_back({"IB_NORMAL_VARIATION", "1"});
  return defines;
}

class IllustrationBuffer final : public Technique {
 public:
  explicit IllustrationBuffer(const Settings& settings)
      : s_(settings),
        counters_(make_buffer(kCounterBytes)),
        pool_("illustration_buffer",
              s_.linearized() ? FragmentPool::Sizing::exact
              : s_.arrays()   ? FragmentPool::Sizing::fixed  // slots per pixel (size_slots)
                              : FragmentPool::Sizing::previous_frame,
              kLargestRecordBytes, [this](uint64_t capacity) { allocate_pool(capacity); }, kSmallestPool) {
    check_combination(s_);
    if (s_.linearized()) list_lengths_.emplace();
    if (s_.ranged()) cursors_.emplace(s_.fill);
    for (const bool arrays : {false, true}) {
      if (arrays ? !s_.may_fill_arrays() : s_.arrays()) continue;
      for (const bool flat : {false, true})
        if (!flat || s_.flat_color_records)
          fills_[arrays][flat] =
              build_geometry_program("algorithms/illustration_buffer/fill.frag", fill_defines(s_, flat, arrays));
    }
    for (const Program* fill : fills()) {
      if (!s_.ranged()) set_uniform(fill->id(), IB_MAX_PER_PIXEL_LOCATION, s_.max_per_pixel);
      if (s_.modulation == Modulation::normal_variation)
        set_uniform(fill->id(), IB_NORMAL_VARIATION_SCALE_LOCATION, s_.normal_variation_scale);
    }
    const ShaderDefines modulate = {{"IB_MODULATE", "1"}, {"IB_PROFILE", std::to_string(int(s_.profile))}};
    compose_ = build_fullscreen_program("algorithms/illustration_buffer/compose.frag",
                                        modulated()          ? modulate
                                        : s_.purely_local() ? ShaderDefines{{"IB_LOCAL_OPACITY", "1"}}
                                                             : ShaderDefines{});
    if (!modulated()) return;
    if (s_.may_sweep()) {  // the swept frames' compose reads the hop distances (sweep_distances.glsl)
      ShaderDefines swept = modulate;
      swept.push_back({"IB_SWEPT", "1"});
      compose_swept_ = build_fullscreen_program("algorithms/illustration_buffer/compose.frag", swept);
    }
    if (s_.heuristic()) {  // neighbors=triangle_index: triangle_search_program, per frame
      neighbors_ = build_compute_program(
          "algorithms/illustration_buffer/neighbors.comp",
          {{"IB_HEURISTIC", "1"}, {"IB_MERGE", s_.neighbors == NeighborSearch::heuristic_merge ? "1" : "0"}});
      set_uniform(neighbors_.id(), IB_WEIGHT_Z_LOCATION, s_.weight_z);
      set_uniform(neighbors_.id(), IB_WEIGHT_N_LOCATION, s_.weight_n);
    }
    build_stylize_programs();
    for (const Program* compose : {&compose_, &compose_swept_})
      if (*compose)
        set_uniform(compose->id(), IB_PROFILE_P_LOCATION, s_.profile == Profile::power ? s_.power_p : s_.exponential_p);
  }

  // The programs of the stylize stages (modulated modes): the init and the
  // diffusion's, for the steps and the sweeps this technique may run.
  void build_stylize_programs() {
    // With skip_converged the init queues the first step's pixels and every
    // step is a listed one; without, every step updates every fragment.
    const bool track = tracks_convergence(s_);
    // stylize_inits_[1] also queues fragments whose alpha differs from a
    // neighbour's (stylize_init.comp, IB_ALPHA_SEEDS): for scenes of more
    // than one alpha, or eq. 5. stylize_init_ queues nothing: for the steps
    // without skip_converged. sweep_init_ writes the sweeps' hop distances
    // and their seed flag, and no field range.
    for (Program* init : {&stylize_init_, &stylize_inits_[0], &stylize_inits_[1], &sweep_init_}) {
      const bool tracked = init == &stylize_inits_[0] || init == &stylize_inits_[1];
      const bool alpha_seeds = init == &stylize_inits_[1], sweeps = init == &sweep_init_;
      const bool needed = sweeps    ? s_.may_sweep()
                          : tracked ? track
                                    : !track && s_.diffusion == Diffusion::steps;
      if (!needed) continue;
      ShaderDefines defines;
      if (tracked) defines.push_back({"IB_TRACK", "1"});
      if (alpha_seeds) defines.push_back({"IB_ALPHA_SEEDS", "1"});
      if (sweeps) defines.push_back({"IB_SWEEP_INIT", "1"});
      if (s_.adaptive_alpha) defines.push_back({"IB_ADAPTIVE", "1"});
      *init = build_compute_program("algorithms/illustration_buffer/stylize_init.comp", defines);
      set_uniform(init->id(), IB_USE_BETA_LOCATION, int(s_.uses_beta()));
      set_uniform(init->id(), IB_USE_GAMMA_LOCATION, int(s_.uses_gamma()));
    }
    if (track) {
      seed_queue_ = build_compute_program("algorithms/illustration_buffer/stylize_seed_queue.comp");
      diffuse_listed_ =
          build_compute_program("algorithms/illustration_buffer/stylize_diffuse.comp", {{"IB_WORKLIST", "1"}});
    } else if (s_.diffusion == Diffusion::steps) {
      stylize_diffuse_ = build_compute_program("algorithms/illustration_buffer/stylize_diffuse.comp");
    }
    if (s_.may_sweep()) {
      diffuse_sweep_ = build_compute_program("algorithms/illustration_buffer/stylize_diffuse.comp", {{"IB_SWEEP", "1"}});
      sweep_check_ = build_compute_program("algorithms/illustration_buffer/stylize_diffuse.comp", {{"IB_CHECK", "1"}});
      sweep_changed_ = make_buffer(4);
      build_field_table();
    }
    for (const Program* p : {&stylize_diffuse_, &diffuse_listed_, &diffuse_sweep_, &sweep_check_}) {
      if (!*p) continue;
      if (p == &diffuse_listed_) set_uniform(p->id(), IB_TOLERANCE_LOCATION, s_.diffusion_tolerance);
      if (uniform_active(p->id(), "u_lambda_alpha")) set_uniform(p->id(), IB_LAMBDA_ALPHA_LOCATION, s_.lambda_alpha);
      set_uniform(p->id(), IB_LAMBDA_BETA_LOCATION, s_.lambda_beta);
      set_uniform(p->id(), IB_LAMBDA_GAMMA_LOCATION, s_.lambda_gamma);
    }
  }

  // The sweeps' beta and gamma by hop distance d (sweep_distances.glsl):
  // F(0) = 1, F(d) = F(d - 1) - lambda in float, as eq. 9 subtracts, and 0
  // from the first value at or below it; iterations + 2 of each (the sweeps
  // run only where `iterations` steps carry 1 to 0: sweep_reaches_steps).
  void build_field_table() {
    field_table_size_ = uint32_t(s_.iterations) + 2;
    std::vector<float> table;
    glm::uvec2 cutoff(field_table_size_);  // each field's first distance of value 0
    for (int field = 0; field < 2; ++field) {
      const std::vector<float> values =
          Settings::values_from_one(field == 0 ? s_.lambda_beta : s_.lambda_gamma, field_table_size_);
      for (uint32_t d = 0; d < field_table_size_; ++d) {
        table.push_back(std::max(values[d], 0.0f));
        if (values[d] <= 0.0f) cutoff[field] = std::min(cutoff[field], d);
      }
    }
    field_table_ = make_buffer(GLsizeiptr(table.size() * sizeof(float)), table.data(), 0);
    field_table_view_ = make_buffer_texture(field_table_, GL_R32F);
    set_uniform(compose_swept_.id(), IB_TABLE_SIZE_LOCATION, field_table_size_);
    for (const Program* p : {&diffuse_sweep_, &sweep_check_}) set_uniform(p->id(), IB_DISTANCE_CUTOFF_LOCATION, cutoff);
    gl_check("illustration_buffer: the sweeps' field table");
  }

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    head_ = make_buffer(GLsizeiptr(width) * height * 4);
    count_ = make_buffer(GLsizeiptr(width) * height * 4);
    const uint64_t pixels = uint64_t(width) * uint64_t(height);
    slots_ = s_.arrays() ? uint32_t(s_.initial_nodes_per_pixel) : 0;  // arrays_where_even: sized on its first arrays frame
    lists_by_tile_.clear();
    pool_.reset(s_.linearized() ? 1 : pixels * s_.initial_nodes_per_pixel);
    no_attachments_ = make_attachmentless_framebuffer(width, height);
    if (s_.ranged()) resize_ranged(width, height);
    if (tracks_convergence(s_)) {
      stamps_ = make_buffer(GLsizeiptr(width) * height * 4);
      pixel_updates_ = make_buffer(GLsizeiptr(width) * height * 4);
      seeds_ = make_buffer(GLsizeiptr(width) * height * 4);
      seeds_view_ = make_buffer_texture(seeds_, GL_R32UI, 0, GLsizeiptr(width) * height * 4);
      const GLsizeiptr list_bytes = kWorklistHeaderBytes + GLsizeiptr(width) * height * 4;
      for (int i = 0; i < 3; ++i) {
        worklists_[i] = make_buffer(list_bytes);
        worklist_views_[i] = make_buffer_texture(worklists_[i], GL_R32UI, 0, list_bytes);
      }
    }
    head_view_ = make_buffer_texture(head_, GL_R32UI, 0, GLsizeiptr(width) * height * 4);
    count_view_ = make_buffer_texture(count_, GL_R32UI, 0, GLsizeiptr(width) * height * 4);
    for (GLuint program : programs()) set_size(program, width, height);
  }

  void render(const Frame& frame) override {
    // Lit scenes: the record keeps the light factor where the linked lists keep their link.
    flat_ = s_.flat_color_records && frame.scene.flat_colors_view() != 0 &&
            (frame.scene.shading() == SceneShading::unlit || s_.ranged());
    flat_table_bytes_ = flat_ ? frame.scene.flat_colors_bytes() : 0;
    arrays_ = fills_arrays(frame);
    const uint32_t longest = arrays_ ? fill_arrays(frame) : s_.linearized() ? fill_linearized(frame) : fill_linked(frame);
    {
      auto stage = frame.clock.stage("sort");
      const GLuint sort = sort_program(longest);
      glUseProgram(sort);
      glBindTextureUnit(IB_FRAGMENT_UNIT, fragment_view_.id());
      if (flat_) glBindTextureUnit(IB_FLAT_COLORS_UNIT, frame.scene.flat_colors_view());
      // Arrays: the fill's counts, which are the kept lengths (count_) unless a list was truncated.
      if (s_.ranged())
        glBindTextureUnit(IB_OFFSETS_UNIT, arrays_ && truncated_lists_ == 0 ? count_view_.id() : offsets_view_.id());
      if (arrays_) set_uniform(sort, IB_SLOTS_LOCATION, slots_);
      if (s_.stores_triangle_vertices()) {
        prepare_scene_data(frame.scene);
        glBindTextureUnit(IB_SORT_TRIANGLES_UNIT, triangles_view_.id());
      }
      run_per_covered_pixel(sort);
      // The dispatch left out the empty pixels: the host checks every range.
      if (s_.linearized() && !arrays_)
        fail_on_mismatched_ranges("illustration_buffer", cursors_->count_mismatched(host_offsets_), produced_);
    }
    bind_sorted_views();
    const GLintptr second_range = second_field_range();
    if (modulated()) stylize(frame, second_range, longest);
    auto stage = frame.clock.stage("compose");
    if (swept_) {  // the hop distances and their table (sweep_distances.glsl)
      glBindTextureUnit(IB_DISTANCES_UNIT, distances_view_.id());
      glBindTextureUnit(IB_FIELD_TABLE_UNIT, field_table_view_.id());
    } else if (modulated()) {
      // The last range written: the init writes the second range, iteration i
      // reads the range i wrote before, so even counts end in the second range.
      const GLintptr last = s_.iterations % 2 == 0 ? second_range : 0;
      bind_fields(last, last == 0 ? second_range : 0);
    }
    frame.bind_target();
    const GLuint compose = swept_ ? compose_swept_.id() : compose_.id();
    glUseProgram(compose);
    frame.set_shared_uniforms(compose);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    for (GLuint unit : {IB_SEARCH_UNIT, IB_FIELDS_UNIT, IB_SHADE_UNIT, IB_WORK_UNIT, IB_HEAD_UNIT, IB_COUNT_UNIT,
                        IB_FRAGMENT_UNIT, IB_SORT_TRIANGLES_UNIT, IB_OFFSETS_UNIT, IB_FLAT_COLORS_UNIT,
                        IB_SEEDS_UNIT, IB_LISTED_PIXELS_UNIT, IB_DISTANCES_UNIT, IB_FIELD_TABLE_UNIT})
      glBindTextureUnit(unit, 0);
  }

  TechniqueCounters counters() const override {
    TechniqueCounters c;
    const uint64_t per_fragment = bytes_per_fragment(s_);
    c.bytes_allocated = uint64_t(width_) * uint64_t(height_) * bytes_per_pixel(s_) + pool_.capacity() * per_fragment +
                        kCounterBytes + triangle_rows_ * 16 + flat_table_bytes_ +
                        (tracks_convergence(s_) ? 3 * kWorklistHeaderBytes : 0) +
                        (s_.may_sweep() ? 4 + 2 * uint64_t(field_table_size_) * sizeof(float) : 0);
    c.fragments_stored = stored_;
    c.fragments_dropped = dropped_;
    c.passes = passes_;
    c.overflow_retries = pool_.overflow_retries() + slot_overflows_;
    c.extra = {{"lists_truncated", double(truncated_lists_)},
               {"linearized_storage", s_.linearized() && !arrays_ ? 1.0 : 0.0, Combine::max},
               {"array_storage", arrays_ ? 1.0 : 0.0, Combine::max},
               {"framebuffer_fetch_fill", fetches_cursors(s_) ? 1.0 : 0.0},
               {"flat_color_records", flat_ ? 1.0 : 0.0},
               {"neighbor_passes", modulated() ? 1.0 : 0.0},
               {"stylize_passes", !modulated() ? 0.0 : swept_ ? double(1 + 5 * sweep_rounds_) : double(1 + s_.iterations)},
               {"dynamic_sort", sorted_dynamically_ ? 1.0 : 0.0, Combine::max},
               {"sweep_diffusion", swept_ ? 1.0 : 0.0, Combine::max}};
    if (modulated() && s_.neighbors == NeighborSearch::triangle_index)
      c.extra.push_back({"isolated_triangles", double(isolated_triangles_), Combine::max});
    if (modulated()) append_neighbor_statistics(c);
    work_saved(c);
    if (swept_) append_sweep_work(c);
    else if (tracks_convergence(s_)) append_diffusion_work(c);
    return c;
  }

  std::vector<DiagnosticImage> diagnostic_images() const override;

 private:
  // The modes with the neighbour search and the stylize stages.
  bool modulated() const { return s_.diffused(); }

  std::vector<const Program*> fills() const {
    std::vector<const Program*> built;
    for (const auto& by_colour : fills_)
      for (const Program& fill : by_colour)
        if (fill) built.push_back(&fill);
    return built;
  }
  const Program& fill_program() const { return fills_[arrays_][flat_]; }

  // storage=linked: stage "clear", then the fill into linked lists, again
  // after a pool overflow (the pool grew). Returns the longest list.
  uint32_t fill_linked(const Frame& frame) {
    GLuint counts[5] = {};  // produced, longest, dropped, truncated, allocated
    const auto clear = [&] {
      fill_buffer_u32(head_, IB_NIL);
      fill_buffer_u32(count_, 0);
      fill_buffer_u32(counters_, 0);
    };
    const auto fill = [&]() -> uint64_t {
      bind_storage();
      draw_scene_pass(frame, fill_program(), no_attachments_);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
      glGetNamedBufferSubData(counters_.id(), 0, sizeof(counts), counts);
      return counts[0];
    };
    passes_ = pool_.fill_until_fits(frame, clear, fill);
    produced_ = counts[0];
    dropped_ = counts[2];
    truncated_lists_ = counts[3];
    stored_ = produced_ - dropped_;
    return counts[1];
  }

  // storage=linearized: stage "count" (the counting pass, the ranges from
  // its counts, the pool sized exactly, the cursors started), then stage
  // "fill". Returns the longest list.
  uint32_t fill_linearized(const Frame& frame) {
    uint32_t longest = 0;
    {
      auto stage = frame.clock.stage("count");
      longest = list_lengths_->longest_list(frame);
      start_exact_ranges(frame, list_lengths_->host_counts(), longest);
    }
    auto stage = frame.clock.stage("fill");
    draw_fill(frame);
    passes_ = 2;
    return longest;
  }

  // The ranges of storage=linearized from every pixel's count, the pool
  // sized exactly and the cursors at the offsets.
  template <class Count>
  void start_exact_ranges(const Frame& frame, const std::vector<Count>& counts, uint32_t longest) {
    upload_ranges(counts, longest > s_.max_per_pixel);
    pool_.before_fill(frame);
    pool_.set_exact(produced_);
    cursors_->start(offsets_);
    remember_lists(frame, longest);
  }

  // The fill of ranged storage: the scene drawn, each fragment at its pixel's cursor.
  void draw_fill(const Frame& frame) {
    bind_storage();
    cursors_->bind_image(IB_CURSORS_IMAGE_UNIT);
    draw_scene_pass(frame, fill_program(), cursors_->fill_framebuffer());
    SlotCursors::unbind_image(IB_CURSORS_IMAGE_UNIT);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }

  // From the counted lengths (the counting pass's floats, or the arrays'
  // final cursors): the fill's ranges (offsets_, linearized), and the sorted
  // ranges and lengths of the kept fragments (head_, count_: the prefix sum
  // of min(count, max_per_pixel), the fill's own offsets unless `truncated`).
  template <class Count>
  void upload_ranges(const std::vector<Count>& counts, bool truncated) {
    offsets_from_counts(counts, host_offsets_);
    if (!arrays_)
      glNamedBufferSubData(offsets_.id(), 0, GLsizeiptr(host_offsets_.size() * 4), host_offsets_.data());
    lengths_from_counts(counts, host_lengths_, s_.max_per_pixel);
    const GLsizeiptr pixel_bytes = GLsizeiptr(host_lengths_.size() * 4);
    glNamedBufferSubData(count_.id(), 0, pixel_bytes, host_lengths_.data());
    produced_ = host_offsets_.back();
    stored_ = produced_;
    truncated_lists_ = 0;
    if (truncated) {
      offsets_from_counts(counts, host_sorted_offsets_, s_.max_per_pixel);
      glNamedBufferSubData(head_.id(), 0, pixel_bytes, host_sorted_offsets_.data());
      stored_ = host_sorted_offsets_.back();
      truncated_lists_ =
          uint64_t(std::count_if(counts.begin(), counts.end(), [&](Count n) { return n > Count(s_.max_per_pixel); }));
    } else {
      glNamedBufferSubData(head_.id(), 0, pixel_bytes, host_offsets_.data());
    }
    dropped_ = produced_ - stored_;
    // Every pixel written, the end advanced past the covered ones: no branch
    // to mispredict on half-covered images (the torus at 256x256: 0.09-0.11
    // against 0.13-0.15 ms).
    covered_pixels_.resize(host_lengths_.size());
    size_t covered = 0;
    for (uint32_t p = 0; p < host_lengths_.size(); ++p) {
      covered_pixels_[covered] = p;
      covered += host_lengths_[p] > 0 ? 1 : 0;
    }
    covered_pixels_.resize(covered);
    if (!covered_pixels_.empty())
      glNamedBufferSubData(covered_.id(), 0, GLsizeiptr(covered_pixels_.size() * 4), covered_pixels_.data());
  }

  // Per-pixel arrays: stage "fill": the fill into arrays of slots_ records,
  // the cursors read back (each pixel's count) and the ranges from them. A
  // list longer than the slots (its cursor passed them) is an overflow
  // retry, nothing is lost: storage=arrays grows the slots to it and fills
  // again; storage=auto fills again into exact ranges from the counts the
  // cursors hold (as after a counting pass), so that a frame whose lists
  // turned uneven never sizes arrays by its longest. Returns the longest list.
  uint32_t fill_arrays(const Frame& frame) {
    auto stage = frame.clock.stage("fill");
    size_slots();
    for (passes_ = 1;; ++passes_) {
      cursors_->start_at_zero();
      set_uniform(fill_program().id(), IB_SLOTS_LOCATION, slots_);
      draw_fill(frame);
      const std::vector<uint32_t>& counts = cursors_->read_back();
      const uint32_t longest = counts.empty() ? 0 : *std::max_element(counts.begin(), counts.end());
      if (longest <= slots_) {
        upload_ranges(counts, longest > s_.max_per_pixel);
        remember_lists(frame, longest);
        if (truncated_lists_ > 0)  // the sort's ib_fill_counts; else the kept lengths are the counts
          glNamedBufferSubData(offsets_.id(), 0, GLsizeiptr(counts.size() * 4), counts.data());
        return longest;
      }
      ++slot_overflows_;
      if (s_.arrays_where_even) {
        arrays_ = false;  // this frame's fill program, sort and range check are linearized's
        start_exact_ranges(frame, counts, longest);
        draw_fill(frame);
        passes_ = 2;
        return longest;
      }
      allocate_slots(longest);
    }
  }

  // Whether this frame fills per-pixel arrays: with storage=arrays always;
  // with arrays_where_even where this tile's last frame had lists whose
  // slots (pixels x longest) held at most kMostSlotsPerFragment times its
  // fragments (no history: the counting pass runs first).
  bool fills_arrays(const Frame& frame) {
    lists_by_tile_.resize(size_t(std::max(frame.tile_count, 1)));
    if (s_.arrays()) return true;
    if (!s_.arrays_where_even) return false;
    const TileLists& last = lists_by_tile_[size_t(std::max(frame.tile_index, 0))];
    const uint64_t slots = uint64_t(width_) * uint64_t(height_) * last.longest;
    return last.fragments > 0 && slots <= kMostSlotsPerFragment * last.fragments;
  }

  // This tile's longest list and fragments (produced_), for the next frame
  // (lists_by_tile_ is sized by fills_arrays, which every frame runs first).
  void remember_lists(const Frame& frame, uint32_t longest) {
    lists_by_tile_[size_t(std::max(frame.tile_index, 0))] = {longest, produced_};
  }

  // Before a fill into per-pixel arrays: as many slots as the longest list
  // any tile of the last frame had (none known: initial_nodes_per_pixel);
  // fewer only when that is less than half of them, so that a view whose
  // longest list wavers does not reallocate every frame.
  void size_slots() {
    uint32_t last = 0;
    for (const TileLists& tile : lists_by_tile_) last = std::max(last, tile.longest);
    const uint32_t wanted = last > 0 ? last : uint32_t(s_.initial_nodes_per_pixel);
    if (wanted > slots_ || 2 * wanted < slots_ || pool_.capacity() < uint64_t(width_) * uint64_t(height_) * slots_)
      allocate_slots(wanted);
  }

  void allocate_slots(uint32_t slots) {
    slots_ = std::max<uint32_t>(slots, 1);
    pool_.reset(uint64_t(width_) * uint64_t(height_) * slots_);
  }

  // The fill's per-pixel ranges (offsets_: linearized's offsets, W*H + 1
  // values, or arrays' counts), the covered-pixel list and the cursors.
  void resize_ranged(int width, int height) {
    const GLsizeiptr pixels = GLsizeiptr(width) * height;
    if (list_lengths_) list_lengths_->resize(width, height);
    offsets_ = make_buffer((pixels + 1) * 4);
    offsets_view_ = make_buffer_texture(offsets_, GL_R32UI, 0, (pixels + 1) * 4);
    covered_ = make_buffer(pixels * 4);
    covered_view_ = make_buffer_texture(covered_, GL_R32UI, 0, pixels * 4);
    cursors_->resize(width, height, "illustration_buffer");
    gl_check("allocating the illustration buffer's per-pixel ranges");
  }

  // Neighbour search, then the fields' initial and boundary conditions
  // (stylize_init) and the `iterations` steps of eq. 8-9 (diffuse).
  void stylize(const Frame& frame, GLintptr second_range, uint32_t longest) {
    {
      auto stage = frame.clock.stage("neighbors");
      if (s_.heuristic()) {
        prepare_scene_data(frame.scene);
        run_per_fragment(neighbors_.id());
      } else {
        const GLuint search = triangle_search_program(longest);
        glUseProgram(search);
        run_per_covered_pixel(search);
      }
    }
    swept_ = sweeps_this_frame(frame.scene);
    const bool track = tracks_convergence(s_) && !swept_;
    {
      auto stage = frame.clock.stage("stylize_init");
      if (track) start_worklists();
      const bool alpha_seeds = track && (s_.adaptive_alpha || !one_alpha(frame.scene));
      if (swept_) {  // sweep_init_ raises the seed flag and writes the distances
        fill_buffer_u32(sweep_changed_, 0);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, IB_SWEEP_CHANGED_BINDING, sweep_changed_.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, IB_DISTANCES_BINDING, distances_.id());
      }
      // Ranges of fragData (dead after the sort) hold the two field buffers.
      bind_fields(0, second_range);
      run_per_fragment(swept_ ? sweep_init_.id() : track ? stylize_inits_[alpha_seeds ? 1 : 0].id() : stylize_init_.id());
      if (track) {
        glUseProgram(seed_queue_.id());
        glBindTextureUnit(IB_SEEDS_UNIT, seeds_view_.id());
        run_per_pixel();  // lists the first step's pixels
      }
      // A listed step writes only the fragments it updates, so both ranges
      // start with every initial value.
      if (track && s_.iterations > 0 && stored_ > 0) {
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glCopyNamedBufferSubData(data_.id(), data_.id(), second_range, 0, kFieldBytes * GLsizeiptr(stored_));
      }
    }
    auto stage = frame.clock.stage("diffuse");
    if (swept_) return sweep_to_fixed_point();
    for (int i = 0; i < s_.iterations; ++i) {
      i % 2 == 0 ? bind_fields(second_range, 0) : bind_fields(0, second_range);
      if (track) run_queued(uint32_t(i + 1));
      else run_per_fragment(stylize_diffuse_.id());
    }
  }

  // Whether this frame's diffusion sweeps (Diffusion): alpha cannot move
  // when eq. 4 gives every fragment the scene's one alpha.
  bool sweeps_this_frame(const SceneGpu& scene) {
    if (!s_.may_sweep()) return false;
    const bool exact = !s_.adaptive_alpha && s_.sweep_reaches_steps() && one_alpha(scene);
    if (!exact && s_.diffusion == Diffusion::sweep)
      throw std::runtime_error("illustration_buffer: diffusion=sweep needs one alpha in the scene (alpha would diffuse "
                               "and the sweeps' fixed point would not be the steps' result); use diffusion=steps or auto");
    return exact;
  }

  // Sweeps in place over the hop distances the init wrote (sweep_distances.glsl):
  // none when the init found no seed (nothing can move); else a round is
  // four raster-order passes, one per diagonal quadrant, then a check;
  // rounds until the check finds nothing that would move. The fields
  // only rise towards the fixed point of eq. 9 (the distances only fall),
  // so any order of updates ends there (README: Diffusion); a round is at
  // least one step, so `iterations` rounds always suffice.
  void sweep_to_fixed_point() {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, IB_SWEEP_CHANGED_BINDING, sweep_changed_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, IB_DISTANCES_BINDING, distances_.id());
    glBindTextureUnit(IB_DISTANCES_UNIT, distances_view_.id());
    sweep_rounds_ = 0;
    GLuint changed = 0;  // here: whether the init found a seed
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(sweep_changed_.id(), 0, sizeof(changed), &changed);
    while (changed != 0 && sweep_rounds_ < uint64_t(s_.iterations)) {
      glUseProgram(diffuse_sweep_.id());
      for (const auto& [dx, dy] : {std::pair{1, 1}, {-1, -1}, {1, -1}, {-1, 1}}) {
        set_uniform(diffuse_sweep_.id(), IB_SWEEP_DIRECTION_LOCATION, glm::ivec2(dx, dy));
        glDispatchCompute(GLuint(height_ + 63) / 64, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
      }
      fill_buffer_u32(sweep_changed_, 0);
      run_per_fragment(sweep_check_.id());
      glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
      glGetNamedBufferSubData(sweep_changed_.id(), 0, sizeof(changed), &changed);
      ++sweep_rounds_;
    }
    gl_check("illustration_buffer: the diffusion's sweeps");
  }

  // The sorted records and ranges as the later passes read them (views.glsl).
  void bind_sorted_views() const {
    glBindTextureUnit(IB_SEARCH_UNIT, search_view_.id());
    glBindTextureUnit(IB_SHADE_UNIT, shade_view_.id());
    glBindTextureUnit(IB_HEAD_UNIT, head_view_.id());
    glBindTextureUnit(IB_COUNT_UNIT, count_view_.id());
  }

  // No pixel queued for any step yet (stamps 0); list 1 receives step 1's
  // (from the init), list 2 step 2's (step k reads list k % 3, fills list
  // (k + 1) % 3 and empties list (k + 2) % 3 for step k + 2).
  void start_worklists() const {
    fill_buffer_u32(stamps_, 0);
    fill_buffer_u32(pixel_updates_, 0);
    fill_buffer_u32(seeds_, 0);
    reset_worklist(worklists_[1]);
    reset_worklist(worklists_[2]);
    bind_storage_buffers({{IB_STAMPS_BINDING, &stamps_},
                          {IB_PIXEL_UPDATES_BINDING, &pixel_updates_},
                          {IB_SEEDS_BINDING, &seeds_},
                          {IB_WORK_OUT_BINDING, &worklists_[1]}});
  }

  static void reset_worklist(const Buffer& list) {
    const GLuint header[4] = {1, 1, 1, 0};  // groups x, y, z (one at least, worklist.glsl); count
    glNamedBufferSubData(list.id(), 0, sizeof(header), header);
  }

  // Step `step` (>= 1) over the pixels queued for it (list step % 3),
  // queueing the next step's pixels in list (step + 1) % 3 (emptied by the
  // step before) and emptying list (step + 2) % 3 for the step after.
  void run_queued(uint32_t step) const {
    const Buffer& in = worklists_[step % 3];
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, IB_WORK_OUT_BINDING, worklists_[(step + 1) % 3].id());
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, IB_WORK_NEXT_BINDING, worklists_[(step + 2) % 3].id(), 0, kWorklistHeaderBytes);
    glBindTextureUnit(IB_WORK_UNIT, worklist_views_[step % 3].id());
    glUseProgram(diffuse_listed_.id());
    set_uniform(diffuse_listed_.id(), IB_NEXT_STEP_LOCATION, step + 1);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, in.id());
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    glDispatchComputeIndirect(0);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  }

  std::vector<GLuint> programs() const {
    std::vector<GLuint> all = {compose_.id()};
    for (const Program* fill : fills()) all.push_back(fill->id());
    for (const Program* p : {&compose_swept_, &neighbors_, &stylize_init_, &stylize_inits_[0], &stylize_inits_[1], &sweep_init_,
                             &seed_queue_, &stylize_diffuse_, &diffuse_listed_, &diffuse_sweep_, &sweep_check_})
      if (*p) all.push_back(p->id());
    for (const auto& [variant, program] : sorts_) all.push_back(program.id());
    for (const auto& [group, program] : triangle_searches_) all.push_back(program.id());
    return all;
  }

  // The sort's local array: the frame's longest list rounded up to a power
  // of two (a few programs serve every frame), at most max_per_pixel. The
  // dynamic sort has no array: one program (keyed 0). Frames with a list
  // longer than the array get the variant that keeps the nearest ones.
  GLuint sort_program(uint32_t longest) {
    const bool dynamic = s_.sort == SortMethod::dynamic ||
                         (s_.sort == SortMethod::automatic && !s_.ranged() && longest <= kLongestDynamicList);
    sorted_dynamically_ = dynamic;
    const uint32_t size =
        dynamic ? 0 : std::min(s_.max_per_pixel, std::max(kSmallestArray, std::bit_ceil(std::max<uint32_t>(longest, 1))));
    const bool truncates = !dynamic && longest > size;
    auto it = sorts_.find({size, flat_, truncates, arrays_});
    if (it == sorts_.end()) {
      ShaderDefines defines = storage_defines(s_, arrays_);
      for (const ShaderDefine& define : per_pixel_defines(s_)) defines.push_back(define);
      if (flat_) defines.push_back({"IB_FLAT_COLOR", "1"});
      if (truncates) defines.push_back({"IB_TRUNCATES", "1"});
      defines.push_back(dynamic ? ShaderDefine{"IB_DYNAMIC", "1"} : ShaderDefine{"IB_ARRAY", std::to_string(size)});
      if (s_.stores_triangle_vertices()) defines.push_back({"IB_TRIANGLE_VERTICES", "1"});
      if (s_.records_surface()) defines.push_back({"IB_SURFACE", "1"});
      it = sorts_.emplace(SortVariant{size, flat_, truncates, arrays_}, build_compute_program("algorithms/illustration_buffer/sort.comp", defines)).first;
      set_size(it->second.id(), width_, height_);
      if (dynamic) set_uniform(it->second.id(), IB_MAX_PER_PIXEL_LOCATION, s_.max_per_pixel);
    }
    return it->second.id();
  }

  // neighbors=triangle_index takes a pixel's fragments IB_GROUP at a time:
  // 4, or the frame's longest kept list rounded up to a power of two where
  // that is shorter (llvmpipe runs the tests of fragments no list has: on
  // the torus's lists of 2, a group of 4 made the search 4.4 ms, not 3.4).
  GLuint triangle_search_program(uint32_t longest) {
    const uint32_t kept = std::max<uint32_t>(std::min(longest, s_.max_per_pixel), 1);
    const uint32_t group = std::min(kLargestSearchGroup, std::bit_ceil(kept));
    auto it = triangle_searches_.find(group);
    if (it == triangle_searches_.end()) {
      it = triangle_searches_
               .emplace(group, build_compute_program("algorithms/illustration_buffer/neighbors_triangle_index.comp",
                                                     search_defines(group)))
               .first;
      set_size(it->second.id(), width_, height_);
    }
    return it->second.id();
  }

  ShaderDefines search_defines(uint32_t group) const {
    ShaderDefines defines = per_pixel_defines(s_);
    defines.push_back({"IB_GROUP", std::to_string(group)});
    return defines;
  }

  void run_per_fragment(GLuint program) const {
    glUseProgram(program);
    set_uniform(program, IB_FRAGMENTS_LOCATION, GLuint(stored_));
    dispatch_in_groups_of_64(stored_);
  }

  // `invocations` in workgroups of 64, two-dimensional beyond 65535 groups
  // (per_fragment.glsl, pixel_dispatch.glsl flatten the index back).
  static void dispatch_in_groups_of_64(uint64_t invocations) {
    const uint64_t groups = (invocations + 63) / 64;
    if (groups > 0) {
      const uint64_t x = std::min<uint64_t>(groups, 65535);
      glDispatchCompute(GLuint(x), GLuint((groups + x - 1) / x), 1);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }

  // The bound `program` (built with per_pixel_defines) once per pixel, or
  // with storage=linearized or arrays once per covered pixel (pixel_dispatch.glsl).
  void run_per_covered_pixel(GLuint program) const {
    if (!s_.ranged()) return run_per_pixel();
    glBindTextureUnit(IB_LISTED_PIXELS_UNIT, covered_view_.id());
    set_uniform(program, IB_LISTED_PIXELS_LOCATION, GLuint(covered_pixels_.size()));
    dispatch_in_groups_of_64(covered_pixels_.size());
  }

  // The bound program once per pixel, in 8x8 workgroups (stylize_seed_queue.comp).
  void run_per_pixel() const {
    glDispatchCompute(GLuint(width_ + 7) / 8, GLuint(height_ + 7) / 8, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }

  void bind_fields(GLintptr in, GLintptr out) const {
    const GLsizeiptr bytes = std::max<GLsizeiptr>(kFieldBytes * GLsizeiptr(stored_), kFieldBytes);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, IB_FIELDS_IN_BINDING, data_.id(), in, bytes);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, IB_FIELDS_OUT_BINDING, data_.id(), out, bytes);
    glBindTextureUnit(IB_FIELDS_UNIT, in == 0 ? fields_view_[0].id() : fields_view_[1].id());
  }

  // Start of the second field range in fragData: aligned for both the SSBO
  // range binding and the buffer-texture view.
  GLintptr second_field_range() const {
    GLint storage = 1, texture = 1;
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &storage);
    glGetIntegerv(GL_TEXTURE_BUFFER_OFFSET_ALIGNMENT, &texture);
    const GLintptr alignment = std::max({storage, texture, 1});
    const GLintptr offset = kFieldBytes * GLintptr(pool_.capacity());
    return (offset + alignment - 1) / alignment * alignment;
  }

  // Whether every triangle of `scene` has the same alpha (then, with eq. 4,
  // every fragment starts with it: stylize_init.comp). Once per scene.
  bool one_alpha(const SceneGpu& uploaded) {
    if (uploaded.serial() != one_alpha_scene_) {
      one_alpha_scene_ = uploaded.serial();
      const Scene& scene = uploaded.scene();
      one_alpha_ = std::all_of(scene.vertices.begin(), scene.vertices.end(),
                               [&](const Vertex& v) { return v.color.a == scene.vertices.front().color.a; });
    }
    return one_alpha_;
  }

  // Once per scene: the bounding-sphere radius (heuristic, eq. 1) or the
  // triangle table (triangle_index).
  void prepare_scene_data(const SceneGpu& uploaded) {
    if (uploaded.serial() == prepared_scene_) return;
    prepared_scene_ = uploaded.serial();
    const Scene& scene = uploaded.scene();
    if (s_.heuristic()) {
      const float radius = scene.bounds().radius;
      set_uniform(neighbors_.id(), IB_INVERSE_RADIUS_LOCATION, radius > 0.0f ? 1.0f / radius : 1.0f);
      return;
    }
    const TriangleTable table = build_triangle_table(scene, s_.weld_vertices);
    const GLsizeiptr bytes = GLsizeiptr(table.vertices_by_stable_id.size() * sizeof(glm::uvec4));
    triangles_ = make_buffer(bytes, table.vertices_by_stable_id.data(), 0);
    triangles_view_ = bytes > 0 ? make_buffer_texture(triangles_, GL_RGBA32UI, 0, bytes) : Texture();
    gl_check("uploading the illustration_buffer triangle table");
    triangle_rows_ = table.vertices_by_stable_id.size();
    isolated_triangles_ = table.isolated_triangles;
  }


  void allocate_pool(uint64_t capacity) {
    if (!s_.ranged()) next_ = make_buffer(GLsizeiptr(capacity) * kNextBytes);  // sort=dynamic's lists
    data_ = make_buffer(GLsizeiptr(capacity) * kFragmentBytes);
    data2_ = make_buffer(GLsizeiptr(capacity) * kSearchBytes);
    data3_ = make_buffer(GLsizeiptr(capacity) * kShadeBytes);
    if (s_.measure_accuracy) truth_ = make_buffer(GLsizeiptr(capacity) * kTruthBytes);
    if (s_.may_sweep()) {
      distances_ = make_buffer(GLsizeiptr(capacity) * kDistanceBytes);
      distances_view_ = make_buffer_texture(distances_, GL_R32UI);
    }
    gl_check("allocating the illustration buffer's fragment pool");
    fragment_view_ = make_buffer_texture(data_, GL_RGBA32UI, 0, GLsizeiptr(capacity) * kFragmentBytes);
    search_view_ = make_buffer_texture(data2_, GL_RGBA32UI, 0, GLsizeiptr(capacity) * kSearchBytes);
    shade_view_ = make_buffer_texture(data3_, GL_RGBA32UI, 0, GLsizeiptr(capacity) * kShadeBytes);
    const GLsizeiptr field_bytes = kFieldBytes * GLsizeiptr(capacity);
    fields_view_[0] = make_buffer_texture(data_, GL_RGBA32F, 0, field_bytes);
    fields_view_[1] = make_buffer_texture(data_, GL_RGBA32F, second_field_range(), field_bytes);
    gl_check("creating the illustration buffer's read-only views");
    if (!s_.ranged())
      for (const Program* fill : fills()) set_uniform(fill->id(), IB_CAPACITY_LOCATION, GLuint(capacity));
  }

  void bind_storage() const {
    bind_storage_buffers({{IB_HEAD_BINDING, &head_},
                          {IB_COUNT_BINDING, &count_},
                          {IB_NEXT_BINDING, &next_},
                          {IB_DATA_BINDING, &data_},
                          {IB_DATA2_BINDING, &data2_},
                          {IB_DATA3_BINDING, &data3_},
                          {IB_COUNTERS_BINDING, &counters_}});
    if (truth_) bind_storage_buffers({{IB_TRUTH_BINDING, &truth_}});
  }

  void append_neighbor_statistics(TechniqueCounters& c) const;
  void append_diffusion_work(TechniqueCounters& c) const;
  void append_sweep_work(TechniqueCounters& c) const;
  void work_saved(TechniqueCounters& c) const;
  // The last frame's per-pixel ranges and sorted records (read back).
  void read_lists(std::vector<uint32_t>& first, std::vector<uint32_t>& count, std::vector<SortedRecord>& sorted) const;

  Settings s_;
  // fills_[arrays][flat]: into per-pixel arrays (IB_ARRAYS) or not; with
  // flat_color_records (no colour in the record: fill.frag) or not.
  // stylize_inits_: with skip_converged's queue ([1]: also alpha seeds); sweep_init_, diffuse_sweep_,
  // sweep_check_, compose_swept_: the frames whose diffusion sweeps.
  Program fills_[2][2], compose_, compose_swept_, neighbors_, stylize_init_, stylize_inits_[2], sweep_init_,
      seed_queue_, stylize_diffuse_,
      diffuse_listed_, diffuse_sweep_, sweep_check_;
  bool flat_ = false;  // this frame's records hold no colour
  uint64_t flat_table_bytes_ = 0;
  // By local array size (0: the dynamic sort), flat colours, whether a list is longer than the array, and
  // whether the fill records are per-pixel arrays.
  using SortVariant = std::tuple<uint32_t, bool, bool, bool>;
  std::map<SortVariant, Program> sorts_;
  std::map<uint32_t, Program> triangle_searches_;  // by IB_GROUP (triangle_search_program)
  bool sorted_dynamically_ = false;    // the last frame's sort
  Buffer counters_, head_, count_, next_, data_, data2_, data3_, truth_, triangles_;
  Buffer stamps_, worklists_[3], pixel_updates_, seeds_;  // skip_converged (worklist.glsl)
  Buffer sweep_changed_;  // diffusion=sweep: 1 when the init found a seed, then when the check found a move
  // diffusion=sweep: each fragment's hop distances, and beta and gamma by distance (sweep_distances.glsl).
  Buffer distances_, field_table_;
  Texture distances_view_, field_table_view_;
  uint32_t field_table_size_ = 0;
  bool swept_ = false;        // the last frame's diffusion swept
  uint64_t sweep_rounds_ = 0;  // and its rounds
  Texture worklist_views_[3], seeds_view_, head_view_, count_view_;
  Texture fragment_view_, search_view_, shade_view_, triangles_view_, fields_view_[2];  // read-only views (views.glsl)
  Framebuffer no_attachments_;
  // storage=linearized: the counting pass; linearized and arrays: the fill's
  // ranges (offsets_: resize_ranged) and cursors (a buffer, or the R32UI
  // target with framebuffer fetch).
  std::optional<ListLengthPass> list_lengths_;
  std::optional<SlotCursors> cursors_;
  // Per-pixel arrays (storage=arrays, or arrays_where_even): whether this
  // frame fills them, the slots per pixel, each tile's last longest list and
  // fragments (size_slots, fills_arrays), and the fills run again for a
  // longer list.
  bool arrays_ = false;
  uint32_t slots_ = 0;
  struct TileLists {
    uint32_t longest = 0;
    uint64_t fragments = 0;
  };
  std::vector<TileLists> lists_by_tile_;
  uint64_t slot_overflows_ = 0;
  Buffer offsets_, covered_;
  Texture offsets_view_, covered_view_;
  // covered_pixels_: the pixels holding a fragment, in raster order (covered_, pixel_dispatch.glsl).
  std::vector<uint32_t> host_offsets_, host_sorted_offsets_, host_lengths_, covered_pixels_;
  // SceneGpu::serial of the scene prepare_scene_data() and one_alpha() last saw (0: none).
  uint64_t prepared_scene_ = 0, one_alpha_scene_ = 0;
  bool one_alpha_ = false;
  int width_ = 0, height_ = 0;
  FragmentPool pool_;
  uint64_t produced_ = 0, stored_ = 0, dropped_ = 0, truncated_lists_ = 0;
  uint64_t passes_ = 0, triangle_rows_ = 0, isolated_triangles_ = 0;
};

// Reads the last frame's lists back (outside the timed frames) and counts
// links per direction, silhouettes and, with measure_accuracy, precision/recall.
void IllustrationBuffer::read_lists(std::vector<uint32_t>& first, std::vector<uint32_t>& count,
                                    std::vector<SortedRecord>& sorted) const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  const size_t pixels = size_t(width_) * size_t(height_);
  first.assign(pixels, 0);
  count.assign(pixels, 0);
  std::vector<SortedSearchRecord> search(stored_);
  std::vector<SortedShadeRecord> shade(stored_);
  glGetNamedBufferSubData(head_.id(), 0, GLsizeiptr(pixels * 4), first.data());
  glGetNamedBufferSubData(count_.id(), 0, GLsizeiptr(pixels * 4), count.data());
  if (stored_ > 0) {
    glGetNamedBufferSubData(data2_.id(), 0, GLsizeiptr(search.size() * sizeof(SortedSearchRecord)), search.data());
    glGetNamedBufferSubData(data3_.id(), 0, GLsizeiptr(shade.size() * sizeof(SortedShadeRecord)), shade.data());
  }
  gl_check("illustration_buffer: reading back the sorted lists");
  sorted.resize(stored_);
  for (size_t i = 0; i < sorted.size(); ++i) sorted[i] = join(search[i], shade[i]);
}

void IllustrationBuffer::append_neighbor_statistics(TechniqueCounters& c) const {
  std::vector<uint32_t> first, count;
  std::vector<SortedRecord> sorted;
  read_lists(first, count, sorted);
  std::vector<TruthRecord> truth(s_.measure_accuracy ? produced_ : 0);
  if (!truth.empty())
    glGetNamedBufferSubData(truth_.id(), 0, GLsizeiptr(truth.size() * sizeof(TruthRecord)), truth.data());
  gl_check("illustration_buffer: reading back the truth records for the neighbour statistics");
  const NeighborStatistics stats =
      neighbor_statistics(width_, height_, first, count, sorted, truth, s_.accuracy_footprints);
  const char* names[4] = {"links_left", "links_right", "links_down", "links_up"};
  for (int d = 0; d < 4; ++d) c.extra.push_back({names[d], double(stats.links[size_t(d)])});
  c.extra.push_back({"silhouette_fragments", double(stats.silhouette_fragments)});
  c.extra.push_back({"link_checksum", double(stats.link_checksum)});
  if (stats.measured) {
    c.extra.push_back({"neighbor_precision", stats.precision, Combine::mean});
    c.extra.push_back({"neighbor_recall", stats.recall, Combine::mean});
  }
}

// passes_skipped: the dispatches modulation=none does not run (the
// neighbour search, the stylize init and its iterations); the modulated path
// issues them whenever the frame stored a fragment. fragments_not_sorted:
// fragments of 1-fragment lists, which the sort copies without walking or
// sorting (read back from the per-pixel counts, outside the frame).
void IllustrationBuffer::work_saved(TechniqueCounters& c) const {
  const double skipped = !modulated() && stored_ > 0 ? double(2 + s_.iterations) : 0.0;
  std::vector<uint32_t> count(size_t(width_) * size_t(height_));
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  if (!count.empty()) glGetNamedBufferSubData(count_.id(), 0, GLsizeiptr(count.size() * 4), count.data());
  gl_check("illustration_buffer: reading back the list lengths");
  // After the sort a count is the kept length: with max_per_pixel = 1 the
  // truncated lists also keep 1, but they were walked.
  const uint64_t single = uint64_t(std::count(count.begin(), count.end(), 1u));
  const uint64_t walked = s_.max_per_pixel == 1 ? truncated_lists_ : 0;
  c.work_saved = {{"passes_skipped", skipped}, {"fragments_not_sorted", double(single - walked)}};
  // storage=linearized or arrays: the empty pixels the sort and the search were not dispatched over.
  const uint64_t empty = s_.ranged() ? count.size() - covered_pixels_.size() : 0;
  c.work_saved.push_back({"empty_pixels_not_dispatched", double(empty)});
}

// fragment_updates: fragments the diffusion recomputed (skip_converged);
// fragment_updates_skipped: the rest of iterations x fragments, each of
// which would have recomputed its own value (read back outside the frame).
void IllustrationBuffer::append_diffusion_work(TechniqueCounters& c) const {
  std::vector<GLuint> per_pixel(size_t(width_) * size_t(height_));
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  if (!per_pixel.empty())
    glGetNamedBufferSubData(pixel_updates_.id(), 0, GLsizeiptr(per_pixel.size() * 4), per_pixel.data());
  gl_check("illustration_buffer: reading back the diffusion's update counts");
  // Every step is a listed one: each pixel counted its own updates.
  uint64_t updates = 0;
  for (GLuint n : per_pixel) updates += n;
  const uint64_t all = stored_ * uint64_t(s_.iterations);
  c.extra.push_back({"fragment_updates", double(updates)});
  c.work_saved.push_back({"fragment_updates_skipped", double(all - std::min<uint64_t>(updates, all))});
}

// sweep_rounds: rounds of four sweeps and a check the last frame ran (the
// last check found nothing to move, unless `iterations` rounds ran out);
// fragment_updates: the fragment updates they computed (every fragment once
// a sweep or check);
// fragment_updates_skipped: what `iterations` steps would have computed beyond.
void IllustrationBuffer::append_sweep_work(TechniqueCounters& c) const {
  const uint64_t updates = 5 * sweep_rounds_ * stored_, all = stored_ * uint64_t(s_.iterations);
  c.extra.push_back({"sweep_rounds", double(sweep_rounds_), Combine::max});
  c.extra.push_back({"fragment_updates", double(updates)});
  c.work_saved.push_back({"fragment_updates_skipped", double(all - std::min(updates, all))});
}

// Neighbour links of each pixel's front fragment (the nearest of its sorted
// list): how many of the 4 were found, and whether one inside the image is
// missing (carnecky2013's silhouette, the seed of the beta field).
std::vector<DiagnosticImage> IllustrationBuffer::diagnostic_images() const {
  if (!modulated() || width_ == 0) return {};  // modulation=none searches no neighbours
  std::vector<uint32_t> first, count;
  std::vector<SortedRecord> sorted;
  read_lists(first, count, sorted);
  const size_t pixels = first.size();
  const float none = std::numeric_limits<float>::quiet_NaN();
  DiagnosticImage links{"neighbor_count",
                        "neighbour links of the front fragment (0-4; image borders count only in-image directions)",
                        width_, height_, std::vector<float>(pixels, none), 0.0f, 4.0f};
  DiagnosticImage silhouette{"silhouette", "1 where the front fragment misses a neighbour inside the image, else 0",
                             width_, height_, std::vector<float>(pixels, none), 0.0f, 1.0f};
  for (size_t p = 0; p < pixels; ++p) {
    const size_t begin = first[p], end = size_t(first[p]) + count[p];
    if (count[p] == 0 || end > sorted.size()) continue;
    const size_t front = begin;  // the sort orders each list front to back
    int found = 0;
    bool missing = false;
    for (uint32_t link : sorted[front].links) {
      if (link == kOffImage) continue;
      if (link == kNoNeighbor) missing = true;
      else ++found;
    }
    links.values[p] = float(found);
    silhouette.values[p] = missing ? 1.0f : 0.0f;
  }
  return {std::move(links), std::move(silhouette)};
}

}  // namespace

std::unique_ptr<Technique> make_illustration_buffer(const Settings& settings) {
  return std::make_unique<IllustrationBuffer>(settings);
}

std::string missing_device_feature(const Settings& settings, const DeviceProfile& device) {
  return settings.ranged() ? missing_slot_fill_feature(settings.fill, device) : "";
}

StorageNeed storage_need(const Settings& settings, const FrameContent& content) {
  // arrays: the first frame's slots, or as many as the longest list;
  // arrays_where_even: the exact count, or arrays where the lists are even.
  const uint64_t arrays = content.pixels() * std::max<uint64_t>(settings.initial_nodes_per_pixel, content.longest_list);
  const uint64_t even = content.pixels() * content.longest_list;
  const uint64_t ranged = settings.arrays() ? arrays
                          : settings.arrays_where_even && even <= kMostSlotsPerFragment * content.fragments
                              ? std::max(content.fragments, even)
                              : content.fragments;
  const uint64_t nodes = std::max(
      settings.ranged() ? ranged : fragment_pool::nodes_for(content, settings.initial_nodes_per_pixel), kSmallestPool);
  return {nodes * uint64_t(kLargestRecordBytes),
          content.pixels() * bytes_per_pixel(settings) + nodes * bytes_per_fragment(settings)};
}

}  // namespace oit::illustration_buffer
