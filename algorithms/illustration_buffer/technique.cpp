// illustration_buffer: per-pixel lists of rich fragment records (fill),
// sorted into contiguous per-pixel ranges (sort), linked to their geodesic
// neighbours in the 4 adjacent pixels (neighbors), transparency fields set
// and diffused along those links (stylize), then blended front to back
// (compose). Each stage is an object of its own (*_stage.h) that owns its
// programs and buffers; they share the records (records.h) and the
// parameter block (frame_params.h), and take the frame's plan
// (frame_plan.h), decided before any of them runs. See README.md for the
// mapping to the papers.
#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "algorithms/illustration_buffer/bindings.h"
#include "algorithms/illustration_buffer/compose_stage.h"
#include "algorithms/illustration_buffer/fill_stage.h"
#include "algorithms/illustration_buffer/neighbor_stage.h"
#include "algorithms/illustration_buffer/settings.h"
#include "algorithms/illustration_buffer/sort_stage.h"
#include "algorithms/illustration_buffer/stylize_stage.h"

namespace oit::illustration_buffer {
namespace {

// Combinations that cannot work, named (the constructor throws them).
void check_combination(const Settings& s) {
  if (s.ranged() && s.sort == SortMethod::dynamic)
    throw std::invalid_argument(
        "illustration_buffer: sort=dynamic sorts the fill's linked lists and needs storage=linked (storage=linearized "
        "and arrays sort each pixel's contiguous range with sort=array or auto)");
  if (s.sort == SortMethod::static_arrays && s.max_per_pixel > IB_STATIC_ENTRIES)
    throw std::invalid_argument("illustration_buffer: sort=static_arrays sorts in pastyrik2016's static arrays of " +
                                std::to_string(IB_STATIC_ENTRIES) + " entries, which cannot keep max_per_pixel=" +
                                std::to_string(s.max_per_pixel) + " fragments; set max_per_pixel <= " +
                                std::to_string(IB_STATIC_ENTRIES) + " or use sort=array");
  if (!s.ranged() && s.fill != SlotFill::automatic)
    throw std::invalid_argument("illustration_buffer: fill=atomic or fill=framebuffer_fetch chooses how "
                                "storage=linearized or arrays takes its slots; with storage=linked leave fill=auto");
  const bool sweep = s.diffused() && s.diffusion == Diffusion::sweep;
  if (sweep && s.field_diffusion == FieldDiffusion::homogeneous)
    throw std::invalid_argument("illustration_buffer: diffusion=sweep reaches the fixed point of eq. 9; "
                                "field_diffusion=homogeneous (eq. 8) needs diffusion=steps or auto");
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

const Settings& checked(const Settings& s) {
  check_combination(s);
  return s;
}

class IllustrationBuffer final : public Technique {
 public:
  explicit IllustrationBuffer(const Settings& settings)
      : s_(checked(settings)),
        params_(s_, uint32_t(s_.iterations)),
        records_(s_),
        fill_(s_, records_, params_),
        sort_(s_, records_),
        neighbors_(s_),
        stylize_(s_, records_, params_),
        compose_(s_) {}

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    params_.values.width = width;
    params_.values.height = height;
    records_.resize(width, height);
    fill_.resize(width, height);
    stylize_.resize(width, height);
  }

  void render(const Frame& frame) override {
    plan_ = plan(frame);
    if (plan_.modulated) neighbors_.prepare(frame.scene, params_);
    fill_result_ = fill_.run(frame, plan_);
    const Grid grid = fill_.grid(fill_result_);
    params_.values.fragments = uint32_t(grid.fragments);
    params_.values.listed_pixels = uint32_t(grid.covered);
    params_.upload();
    sort_choice_ = sort_.choose(fill_result_);
    sort_.run(frame, plan_, fill_result_, sort_choice_, fill_, grid);
    records_.bind_sorted_views();
    const GLintptr second_range = records_.second_field_range();
    if (plan_.modulated) {
      neighbors_.run(frame, fill_result_.longest, grid);
      stylize_.run(frame, plan_, grid, second_range);
      stylize_.bind_result(plan_, grid, second_range);
    }
    compose_.run(frame, plan_);
  }

  TechniqueCounters counters() const override;
  std::vector<DiagnosticImage> diagnostic_images() const override;

 private:
  // The frame's plan, before any pass runs.
  FramePlan plan(const Frame& frame) {
    FramePlan p;
    p.storage = fill_.planned_storage(frame);
    // Lit scenes: the record keeps the light factor where the linked lists keep their link.
    p.flat_records = s_.flat_color_records && frame.scene.flat_colors_view() != 0 &&
                     (frame.scene.shading() == SceneShading::unlit || s_.ranged());
    p.modulated = s_.diffused();
    p.swept = p.modulated && stylize_.sweeps(frame.scene);
    p.tracked = s_.tracks_convergence() && !p.swept;
    p.alpha_seeds = p.tracked && (s_.adaptive_alpha || !stylize_.one_alpha(frame.scene));
    p.tile = std::max(frame.tile_index, 0);
    p.tiles = std::max(frame.tile_count, 1);
    flat_table_bytes_ = p.flat_records ? frame.scene.flat_colors_bytes() : 0;
    return p;
  }

  void append_neighbor_statistics(TechniqueCounters& c) const;
  void append_work_saved(TechniqueCounters& c) const;

  const Settings s_;
  FrameParams params_;
  Records records_;
  FillStage fill_;
  SortStage sort_;
  NeighborStage neighbors_;
  StylizeStage stylize_;
  ComposeStage compose_;
  int width_ = 0, height_ = 0;
  // The last frame's plan and outcomes (counters, diagnostic images).
  FramePlan plan_;
  FillResult fill_result_;
  SortChoice sort_choice_;
  uint64_t flat_table_bytes_ = 0;
};

TechniqueCounters IllustrationBuffer::counters() const {
  TechniqueCounters c;
  const FillResult& f = fill_result_;
  c.bytes_allocated = uint64_t(width_) * uint64_t(height_) * bytes_per_pixel(s_) +
                      records_.capacity() * bytes_per_fragment(s_) + kCounterBytes + sort_.triangle_rows() * 16 +
                      flat_table_bytes_ + stylize_.bytes_allocated();
  c.fragments_stored = f.stored;
  c.fragments_dropped = f.dropped;
  c.passes = f.passes;
  c.overflow_retries = records_.pool().overflow_retries() + fill_.slot_overflows();
  c.extra = {{"lists_truncated", double(f.truncated_lists)},
             {"linearized_storage", f.linearized() ? 1.0 : 0.0, Combine::max},
             {"array_storage", f.arrays() ? 1.0 : 0.0, Combine::max},
             {"framebuffer_fetch_fill", fill_.fetches_cursors() ? 1.0 : 0.0},
             {"flat_color_records", plan_.flat_records ? 1.0 : 0.0},
             {"neighbor_passes", plan_.modulated ? 1.0 : 0.0},
             {"stylize_passes", stylize_.passes(plan_)},
             {"dynamic_sort", sort_choice_.dynamic ? 1.0 : 0.0, Combine::max},
             {"static_arrays_sort", sort_choice_.static_arrays ? 1.0 : 0.0, Combine::max},
             {"sweep_diffusion", plan_.swept ? 1.0 : 0.0, Combine::max}};
  if (plan_.modulated && s_.neighbors == NeighborSearch::triangle_index)
    c.extra.push_back({"isolated_triangles", double(sort_.isolated_triangles()), Combine::max});
  if (plan_.modulated) append_neighbor_statistics(c);
  append_work_saved(c);
  stylize_.append_work(c, plan_, f.stored);
  return c;
}

// Reads the last frame's lists back (outside the timed frames) and counts
// links per direction, silhouettes and, with measure_accuracy, precision/recall.
void IllustrationBuffer::append_neighbor_statistics(TechniqueCounters& c) const {
  std::vector<uint32_t> first, count;
  std::vector<SortedRecord> sorted;
  records_.read_lists(fill_result_.stored, first, count, sorted);
  const std::vector<TruthRecord> truth = records_.read_truth(fill_result_.produced);
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
void IllustrationBuffer::append_work_saved(TechniqueCounters& c) const {
  const double skipped = !plan_.modulated && fill_result_.stored > 0 ? double(2 + s_.iterations) : 0.0;
  const std::vector<uint32_t> count = records_.read_counts();
  // After the sort a count is the kept length: with max_per_pixel = 1 the
  // truncated lists also keep 1, but they were walked.
  const uint64_t single = uint64_t(std::count(count.begin(), count.end(), 1u));
  const uint64_t walked = s_.max_per_pixel == 1 ? fill_result_.truncated_lists : 0;
  c.work_saved = {{"passes_skipped", skipped}, {"fragments_not_sorted", double(single - walked)}};
  // storage=linearized or arrays: the empty pixels the sort and the search were not dispatched over.
  const uint64_t empty = s_.ranged() ? count.size() - fill_.covered_pixels() : 0;
  c.work_saved.push_back({"empty_pixels_not_dispatched", double(empty)});
}

// Neighbour links of each pixel's front fragment (the nearest of its sorted
// list): how many of the 4 were found, and whether one inside the image is
// missing (carnecky2013's silhouette, the seed of the beta field).
std::vector<DiagnosticImage> IllustrationBuffer::diagnostic_images() const {
  if (!s_.diffused() || width_ == 0) return {};  // modulation=none searches no neighbours
  std::vector<uint32_t> first, count;
  std::vector<SortedRecord> sorted;
  records_.read_lists(fill_result_.stored, first, count, sorted);
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
