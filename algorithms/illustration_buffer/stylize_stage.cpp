#include "algorithms/illustration_buffer/stylize_stage.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "algorithms/illustration_buffer/bindings.h"
#include "algorithms/illustration_buffer/shader_variant.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"

namespace oit::illustration_buffer {
namespace {

constexpr const char* kInit = "algorithms/illustration_buffer/stylize_init.comp";
constexpr const char* kDiffuse = "algorithms/illustration_buffer/stylize_diffuse.comp";

Program build_diffusion(ShaderVariant::Diffuse pass, const Settings& s) {
  ShaderVariant v;
  v.diffuse = pass;
  v.homogeneous_fields = s.field_diffusion == FieldDiffusion::homogeneous;
  return build_compute_program(kDiffuse, v.defines());
}

void reset_worklist(const Buffer& list) {
  const GLuint header[4] = {1, 1, 1, 0};  // groups x, y, z (one at least, worklist.glsl); count
  glNamedBufferSubData(list.id(), 0, sizeof(header), header);
}

}  // namespace

StylizeStage::StylizeStage(const Settings& s, Records& records, FrameParams& params)
    : s_(s), records_(records), params_(params) {
  if (!s_.diffused()) return;
  build_inits();
  // With skip_converged every step is a listed one; without, every step
  // updates every fragment.
  if (s_.tracks_convergence()) {
    seed_queue_ = build_compute_program("algorithms/illustration_buffer/stylize_seed_queue.comp");
    diffuse_listed_ = build_diffusion(ShaderVariant::Diffuse::worklist, s_);
  } else if (s_.diffusion == Diffusion::steps) {
    diffuse_ = build_diffusion(ShaderVariant::Diffuse::plain, s_);
  }
  if (s_.may_sweep()) {
    diffuse_sweep_ = build_diffusion(ShaderVariant::Diffuse::sweep, s_);
    sweep_check_ = build_diffusion(ShaderVariant::Diffuse::check, s_);
    sweep_changed_ = make_buffer(4);
    build_field_table(params);
  }
}

// With skip_converged the init queues the first step's pixels
// (tracked_inits_[1] also where a neighbour's alpha differs:
// stylize_init.comp, IB_ALPHA_SEEDS, for scenes of more than one alpha, or
// eq. 5); init_ queues nothing: for the steps without skip_converged.
// sweep_init_ writes the sweeps' hop distances and their seed flag, and no
// field range.
void StylizeStage::build_inits() {
  const bool track = s_.tracks_convergence();
  const auto build = [&](Program& init, bool tracked, bool alpha_seeds, bool sweeps) {
    ShaderVariant v;
    v.track = tracked;
    v.alpha_seeds = alpha_seeds;
    v.sweep_init = sweeps;
    v.adaptive = s_.adaptive_alpha;
    init = build_compute_program(kInit, v.defines());
  };
  if (!track && s_.diffusion == Diffusion::steps) build(init_, false, false, false);
  if (track) {
    build(tracked_inits_[0], true, false, false);
    build(tracked_inits_[1], true, true, false);
  }
  if (s_.may_sweep()) build(sweep_init_, false, false, true);
}

// The sweeps' beta and gamma by hop distance d (sweep_distances.glsl):
// F(0) = 1, F(d) = F(d - 1) - lambda in float, as eq. 9 subtracts, and 0
// from the first value at or below it; iterations + 2 of each (the sweeps
// run only where `iterations` steps carry 1 to 0: sweep_reaches_steps).
void StylizeStage::build_field_table(FrameParams& params) {
  field_table_size_ = uint32_t(s_.iterations) + 2;
  std::vector<float> table;
  uint32_t cutoff[2] = {field_table_size_, field_table_size_};  // each field's first distance of value 0
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
  params.values.table_size = field_table_size_;
  params.values.cutoff_beta = cutoff[0];
  params.values.cutoff_gamma = cutoff[1];
  gl_check("illustration_buffer: the sweeps' field table");
}

void StylizeStage::resize(int width, int height) {
  width_ = width;
  height_ = height;
  if (!s_.diffused() || !s_.tracks_convergence()) return;
  const GLsizeiptr pixel_bytes = GLsizeiptr(width) * height * 4;
  stamps_ = make_buffer(pixel_bytes);
  pixel_updates_ = make_buffer(pixel_bytes);
  seeds_ = make_buffer(pixel_bytes);
  seeds_view_ = make_buffer_texture(seeds_, GL_R32UI, 0, pixel_bytes);
  const GLsizeiptr list_bytes = kWorklistHeaderBytes + pixel_bytes;
  for (int i = 0; i < 3; ++i) {
    worklists_[i] = make_buffer(list_bytes);
    worklist_views_[i] = make_buffer_texture(worklists_[i], GL_R32UI, 0, list_bytes);
  }
}

bool StylizeStage::sweeps(const SceneGpu& scene) {
  if (!s_.may_sweep()) return false;
  const bool exact = !s_.adaptive_alpha && s_.sweep_reaches_steps() && one_alpha(scene);
  if (!exact && s_.diffusion == Diffusion::sweep)
    throw std::runtime_error("illustration_buffer: diffusion=sweep needs one alpha in the scene (alpha would diffuse "
                             "and the sweeps' fixed point would not be the steps' result); use diffusion=steps or auto");
  return exact;
}

bool StylizeStage::one_alpha(const SceneGpu& uploaded) {
  if (uploaded.serial() != one_alpha_scene_) {
    one_alpha_scene_ = uploaded.serial();
    const Scene& scene = uploaded.scene();
    one_alpha_ = std::all_of(scene.vertices.begin(), scene.vertices.end(),
                             [&](const Vertex& v) { return v.color.a == scene.vertices.front().color.a; });
  }
  return one_alpha_;
}

void StylizeStage::run(const Frame& frame, const FramePlan& plan, const Grid& grid, GLintptr second_range) {
  {
    auto stage = frame.clock.stage("stylize_init");
    if (plan.tracked) start_worklists();
    if (plan.swept) {  // sweep_init_ raises the seed flag and writes the distances
      if (distances_capacity_ != records_.capacity()) {
        distances_capacity_ = records_.capacity();
        distances_ = make_buffer(GLsizeiptr(distances_capacity_) * kDistanceBytes);
        distances_view_ = make_buffer_texture(distances_, GL_R32UI);
        gl_check("allocating the sweeps' hop distances");
      }
      fill_buffer_u32(sweep_changed_, 0);
      bind_storage_buffers({{IB_SWEEP_CHANGED_BINDING, &sweep_changed_}, {IB_DISTANCES_BINDING, &distances_}});
    }
    // Ranges of fragData (dead after the sort) hold the two field buffers.
    records_.bind_fields(0, second_range, grid.fragments);
    grid.per_fragment(plan.swept    ? sweep_init_.id()
                      : plan.tracked ? tracked_inits_[plan.alpha_seeds ? 1 : 0].id()
                                     : init_.id());
    if (plan.tracked) {
      glUseProgram(seed_queue_.id());
      glBindTextureUnit(IB_SEEDS_UNIT, seeds_view_.id());
      grid.per_pixel();  // lists the first step's pixels
    }
    // A listed step writes only the fragments it updates, so both ranges
    // start with every initial value.
    if (plan.tracked && s_.iterations > 0 && grid.fragments > 0) {
      glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
      records_.copy_fields(second_range, 0, grid.fragments);
    }
  }
  auto stage = frame.clock.stage("diffuse");
  if (plan.swept) return sweep_to_fixed_point(grid);
  for (int i = 0; i < s_.iterations; ++i) {
    i % 2 == 0 ? records_.bind_fields(second_range, 0, grid.fragments) : records_.bind_fields(0, second_range, grid.fragments);
    if (plan.tracked) run_queued(uint32_t(i + 1));
    else grid.per_fragment(diffuse_.id());
  }
}

// No pixel queued for any step yet (stamps 0); list 1 receives step 1's
// (from the init), list 2 step 2's (step k reads list k % 3, fills list
// (k + 1) % 3 and empties list (k + 2) % 3 for step k + 2).
void StylizeStage::start_worklists() const {
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

// Step `step` (>= 1) over the pixels queued for it (list step % 3),
// queueing the next step's pixels in list (step + 1) % 3 (emptied by the
// step before) and emptying list (step + 2) % 3 for the step after.
void StylizeStage::run_queued(uint32_t step) const {
  const Buffer& in = worklists_[step % 3];
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, IB_WORK_OUT_BINDING, worklists_[(step + 1) % 3].id());
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, IB_WORK_NEXT_BINDING, worklists_[(step + 2) % 3].id(), 0,
                    kWorklistHeaderBytes);
  glBindTextureUnit(IB_WORK_UNIT, worklist_views_[step % 3].id());
  glUseProgram(diffuse_listed_.id());
  params_.bind_step(step);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, in.id());
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  glDispatchComputeIndirect(0);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

// Sweeps in place over the hop distances the init wrote (sweep_distances.glsl):
// none when the init found no seed (nothing can move); else a round is
// four raster-order passes, one per diagonal quadrant, then a check;
// rounds until the check finds nothing that would move. The fields
// only rise towards the fixed point of eq. 9 (the distances only fall),
// so any order of updates ends there (README: Diffusion); a round is at
// least one step, so `iterations` rounds always suffice.
void StylizeStage::sweep_to_fixed_point(const Grid& grid) {
  glBindTextureUnit(IB_DISTANCES_UNIT, distances_view_.id());
  sweep_rounds_ = 0;
  GLuint changed = 0;  // here: whether the init found a seed
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(sweep_changed_.id(), 0, sizeof(changed), &changed);
  while (changed != 0 && sweep_rounds_ < uint64_t(s_.iterations)) {
    glUseProgram(diffuse_sweep_.id());
    for (uint32_t direction = 0; direction < FrameParams::kSweeps; ++direction) {
      params_.bind_sweep(direction);
      glDispatchCompute(GLuint(height_ + 63) / 64, 1, 1);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    fill_buffer_u32(sweep_changed_, 0);
    grid.per_fragment(sweep_check_.id());
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(sweep_changed_.id(), 0, sizeof(changed), &changed);
    ++sweep_rounds_;
  }
  gl_check("illustration_buffer: the diffusion's sweeps");
}

void StylizeStage::bind_result(const FramePlan& plan, const Grid& grid, GLintptr second_range) const {
  if (plan.swept) {  // the hop distances and their table (sweep_distances.glsl)
    glBindTextureUnit(IB_DISTANCES_UNIT, distances_view_.id());
    glBindTextureUnit(IB_FIELD_TABLE_UNIT, field_table_view_.id());
    return;
  }
  // The last range written: the init writes the second range, iteration i
  // reads the range i wrote before, so even counts end in the second range.
  const GLintptr last = s_.iterations % 2 == 0 ? second_range : 0;
  records_.bind_fields(last, last == 0 ? second_range : 0, grid.fragments);
}

double StylizeStage::passes(const FramePlan& plan) const {
  return !plan.modulated ? 0.0 : plan.swept ? double(1 + 5 * sweep_rounds_) : double(1 + s_.iterations);
}

// With sweeps: sweep_rounds, the rounds of four sweeps and a check the last
// frame ran (the last check found nothing to move, unless `iterations`
// rounds ran out); fragment_updates, the updates they computed (every
// fragment once a sweep or check). With listed steps: fragment_updates, the
// fragments the steps recomputed. fragment_updates_skipped: what
// `iterations` steps over every fragment would have computed beyond.
void StylizeStage::append_work(TechniqueCounters& c, const FramePlan& plan, uint64_t stored) const {
  const uint64_t all = stored * uint64_t(s_.iterations);
  uint64_t updates = 0;
  if (plan.swept) {
    updates = 5 * sweep_rounds_ * stored;
    c.extra.push_back({"sweep_rounds", double(sweep_rounds_), Combine::max});
  } else if (s_.tracks_convergence()) {
    std::vector<GLuint> per_pixel(size_t(width_) * size_t(height_));
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (!per_pixel.empty())
      glGetNamedBufferSubData(pixel_updates_.id(), 0, GLsizeiptr(per_pixel.size() * 4), per_pixel.data());
    gl_check("illustration_buffer: reading back the diffusion's update counts");
    for (GLuint n : per_pixel) updates += n;  // every step is a listed one: each pixel counted its own
  } else {
    return;
  }
  c.extra.push_back({"fragment_updates", double(updates)});
  c.work_saved.push_back({"fragment_updates_skipped", double(all - std::min<uint64_t>(updates, all))});
}

uint64_t StylizeStage::bytes_allocated() const {
  return (s_.tracks_convergence() ? 3 * kWorklistHeaderBytes : 0) +
         (s_.may_sweep() ? 4 + 2 * uint64_t(field_table_size_) * sizeof(float) : 0);
}

}  // namespace oit::illustration_buffer
