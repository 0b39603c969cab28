#include "harness/app/commands.h"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <optional>
#include <set>

#include "harness/app/bench_files.h"
#include "harness/app/bench_report.h"
#include "harness/app/huge_page_malloc.h"
#include "harness/gl/shader_capabilities.h"
#include "harness/output/heatmap.h"
#include "scenes/cameras.h"
#include "harness/run/results_csv.h"
#include "harness/gl/program_cache.h"
#include "scenes/scene_library.h"
#include "oit_revision.h"

namespace oit {
namespace {

std::unique_ptr<GlContext> open_context(const CommonOptions& common) {
  return create_headless_context(parse_device_choice(common.device), common.debug_gl);
}

void print_params(const ParamSchema& schema) {
  for (const auto& p : schema) {
    char head[96];
    std::snprintf(head, sizeof head, "      %-24s default %-8s ", p.name.c_str(), p.default_value.c_str());
    const std::string line = head + p.range_text() + " — " + p.description;
    std::printf("%s\n", wrap_text(line, terminal_width(), 8).c_str());
  }
}

// Text for a Markdown table cell: a cell ends at '|' and its row at a line
// break, so a '|' in the text is escaped and a line break becomes a space.
std::string markdown_cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c == '\n' ? ' ' : c);
  return out;
}

}  // namespace

std::string platform_text(const DeviceProfile& device) {
  return device.platform + ", host pages " + host_page_policy() + ", " + atomics_path();
}

RunContext run_context(const DeviceProfile& device) {
  return {device.renderer, device.version, platform_text(device), OIT_GIT_REVISION, utc_timestamp()};
}

std::string technique_table_markdown(const TechniqueRegistry& registry) {
  std::string table =
      "| id | technique | paper | kind | parameters (default, range) | stages |\n|---|---|---|---|---|---|\n";
  for (const auto& t : registry.all()) {
    std::string params, stages;
    for (const auto& p : t.params) {
      const std::string default_text = p.default_value.empty() ? "empty" : p.default_value;
      params += (params.empty() ? "" : ", ") + ("`" + p.name + "` (" + default_text + "; " + p.range_text() + ")");
    }
    for (const auto& stage : t.stages) stages += (stages.empty() ? "" : ", ") + stage;
    const std::string kind = t.is_reference ? "exact (the reference)" : to_string(t.exactness);
    table += "| `" + t.id + "` | " + markdown_cell(t.display_name) + " | " + markdown_cell(t.paper) + " | " + kind +
             " | " + markdown_cell(params.empty() ? "-" : params) + " | " + stages + " |\n";
  }
  return table;
}

std::string technique_params_markdown(const TechniqueDescriptor& technique) {
  if (technique.params.empty()) return "`" + technique.id + "` has no parameters.\n";
  std::string table = "| parameter | default | range | description |\n|---|---|---|---|\n";
  for (const auto& p : technique.params) {
    const std::string default_text = p.default_value.empty() ? "empty" : "`" + p.default_value + "`";
    table += "| `" + p.name + "` | " + default_text + " | " + markdown_cell(p.range_text()) + " | " +
             markdown_cell(p.description) + " |\n";
  }
  return table;
}

int run_list(const CommonOptions& common) {
  auto context = open_context(common);
  const DeviceProfile& device = context->device();
  std::printf("Device: %s (%s, %s)%s\n", device.renderer.c_str(), device.version.c_str(), platform_text(device).c_str(),
              device.software ? " — software GL: stage clock defaults to wall+glFinish" : "");
  // The profile the techniques' resolution rules receive (device_profile.h).
  for (const std::string& line : device.describe())
    std::printf("%s\n", wrap_text("    " + line, terminal_width(), 8).c_str());
  std::printf("\n");
  const DeviceLimits limits = query_device_limits();
  std::printf("Limits: largest buffer %s (storage block, buffer texture); memory budget %s (%s). A technique whose storage for a frame "
              "exceeds either renders in screen tiles (CSV column `tiles`; --memory-budget sets the budget).\n\n",
              format_bytes(limits.largest_buffer).c_str(), format_bytes(limits.memory_budget).c_str(),
              limits.budget_source.c_str());
  std::printf("EGL devices (--device egl:N):\n");
  for (const auto& line : describe_egl_devices()) std::printf("    %s\n", line.c_str());
  std::printf("\nTechniques:\n");
  for (const auto& t : builtin_techniques().all()) {
    std::string stages;
    for (const auto& s : t.stages) stages += (stages.empty() ? "" : ", ") + s;
    std::printf("  %-20s %s [%s%s]\n      paper: %s\n      stages: %s\n", t.id.c_str(), t.display_name.c_str(),
                to_string(t.exactness), t.is_reference ? ", reference" : "",
                t.paper.c_str(), stages.c_str());
    print_params(t.params);
  }
  std::printf("\nScenes (or a .gltf/.glb/.obj/.off/.ply/.stl file path):\n");
  for (const auto& s : scene_library()) {
    std::printf("  %-20s %s\n", s.id.c_str(), s.description.c_str());
    print_params(s.params);
  }
  return 0;
}

std::string per_view_path(const std::string& out, size_t index) {
  const auto dot = out.find_last_of('.');
  const auto slash = out.find_last_of('/');
  const bool has_extension = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  const std::string suffix = "_cam" + std::to_string(index);
  return has_extension ? out.substr(0, dot) + suffix + out.substr(dot) : out + suffix;
}

namespace {

// "max error X, rmse Y vs reference", or why there is no reference.
std::string error_text(const RunResult& result) {
  if (!result.error) return result.message;
  char text[96];
  std::snprintf(text, sizeof text, "max error %.3g, rmse %.3g vs reference", result.error->max_abs, result.error->rmse);
  return text;
}

}  // namespace

int run_render(const CommonOptions& common, const RenderOptions& options) {
  const std::vector<std::string> cameras = expand_camera_spec(options.camera);
  auto context = open_context(common);
  Harness harness(*context, builtin_techniques());
  for (size_t view = 0; view < cameras.size(); ++view) {
    RunSpec spec;
    spec.technique = options.technique;
    for (const auto& s : options.sets) parse_assignment(s, spec.params);
    spec.scene = options.scene;
    for (const auto& s : options.scene_sets) parse_assignment(s, spec.scene_params);
    spec.camera = cameras[view];
    parse_size(size_for(options.size, harness.device()), spec.width, spec.height);
    spec.background = parse_background(options.background);
    spec.scene_rect = parse_on_off("--scene-rect", options.scene_rect);
    if (!options.memory_budget.empty()) spec.memory_budget = parse_memory_size(options.memory_budget);
    spec.warmup = 0;
    spec.frames = 1;
    RunResult result = harness.run(spec);
    if (result.status != RunStatus::ok) {
      std::fprintf(stderr, "oitbench render: %s %s: %s\n", options.technique.c_str(), to_string(result.status).c_str(),
                   result.message.c_str());
      return 1;
    }
    const std::string out = cameras.size() > 1 ? per_view_path(options.out, view) : options.out;
    write_image(result.image, out, parse_png_encoding(options.png));
    std::printf("%s on %s %dx%d%s -> %s (%s)\n", options.technique.c_str(), options.scene.c_str(), spec.width,
                spec.height, spec.camera == "default" ? "" : (" camera " + spec.camera).c_str(), out.c_str(),
                error_text(result).c_str());
  }
  return 0;
}

namespace {

std::string clock_name(const BenchOptions& options, const Harness& harness) {
  return options.sweep.clock == "auto" ? to_string(harness.default_clock()) : options.sweep.clock;
}

// One sweep of `bench`: the files it writes and what it has done so far.
class BenchSession {
 public:
  BenchSession(Harness& harness, const BenchOptions& options)
      : harness_(harness), options_(options), csv_(options.csv), context_(run_context(harness.device())) {
    // The CSV repairs a torn end first, so only whole runs count.
    if (options.resume) {
      finished_ = csv_.finished_runs();
      claims_.emplace(options.csv);
    }
    if (!options.samples.empty()) samples_.emplace(options.samples);
    if (!options.json.empty()) json_.emplace(options.json, context_);
  }

  void run_all(const std::vector<RunSpec>& runs) {
    const Progress progress(runs.size());
    for (size_t begin = 0; begin < runs.size();) {
      size_t end = begin + 1;
      while (end < runs.size() && same_block(runs[begin], runs[end])) ++end;
      if (options_.rounds > 1 && end - begin > 1) run_interleaved(runs, begin, end, progress);
      else
        for (size_t i = begin; i < end; ++i) run_alone(runs, i, progress);
      begin = end;
    }
  }

  // The summary and the totals; the exit code.
  int report() const;

 private:
  static bool same_block(const RunSpec& a, const RunSpec& b) {
    return a.scene == b.scene && a.scene_params == b.scene_params && a.camera == b.camera && a.width == b.width &&
           a.height == b.height && a.scene_rect == b.scene_rect;
  }
  void run_alone(const std::vector<RunSpec>& runs, size_t i, const Progress& progress);
  // Runs [begin, end) of one block in interleaved rounds (BenchOptions::rounds).
  void run_interleaved(const std::vector<RunSpec>& runs, size_t begin, size_t end, const Progress& progress);
  // Whether the run is to be left out (--resume: done, or claimed by another
  // process); `outcome` then says why. Otherwise its claim, when resuming.
  bool leave_out(const RunSpec& spec, std::optional<RunClaims::Claim>& claim, std::string& outcome);
  // Each returns what happened, for the progress line.
  std::string record(RunResult result);
  // The names of the images written (none without --images).
  std::string write_images(const RunResult& result) const;

  Harness& harness_;
  const BenchOptions& options_;
  CsvWriter csv_;
  RunContext context_;
  std::set<RunKey> finished_;
  std::optional<RunClaims> claims_;
  std::optional<SamplesCsv> samples_;
  std::optional<BenchJson> json_;
  std::vector<RunResult> results_;
  std::string images_;  // the last run's image files (write_images)
  size_t resumed_ = 0, elsewhere_ = 0;
};

bool BenchSession::leave_out(const RunSpec& spec, std::optional<RunClaims::Claim>& claim, std::string& outcome) {
  const auto key = options_.resume ? resume_key(spec, builtin_techniques()) : std::nullopt;
  if (!key) return false;
  // Claimed before it runs, then looked up again: another --resume process
  // on this file may have run it meanwhile, or be running it now.
  if (!finished_.count(*key))
    if (auto taken = claims_->try_claim(*key)) claim.emplace(std::move(*taken));
  if (!finished_.count(*key) && !claim) {
    ++elsewhere_;
    outcome = "being run by another bench --resume on " + options_.csv + ", left to it";
    return true;
  }
  if (finished_.count(*key) || csv_.finished_runs().count(*key)) {
    ++resumed_;
    outcome = "already in " + options_.csv + ", not run again";
    return true;
  }
  return false;
}

void BenchSession::run_alone(const std::vector<RunSpec>& runs, size_t i, const Progress& progress) {
  const std::string start = progress.start_text(i, runs[i]);
  std::fputs(start.c_str(), stderr);  // before the run: what is running now
  images_.clear();
  std::optional<RunClaims::Claim> claim;
  std::string outcome;
  if (!leave_out(runs[i], claim, outcome)) outcome = record(harness_.run(runs[i]));
  outcome += progress.timing_text(i + 1);
  std::fprintf(stderr, "%s\n", wrap_after(start.size(), outcome).c_str());
  // On a line of their own: paths are long, and a script finds them there.
  if (!images_.empty()) std::fprintf(stderr, "  images: %s\n", images_.c_str());
}

namespace {

// A run's total samples grouped by the round each frame ran in.
std::vector<std::vector<double>> samples_by_round(const RunResult& result) {
  std::vector<std::vector<double>> rounds(size_t(std::max(result.rounds, 0)));
  const StageResult* total = result.total();
  if (!total) return rounds;
  for (size_t i = 0; i < total->samples_ms.size() && i < result.frame_rounds.size(); ++i)
    rounds[size_t(result.frame_rounds[i])].push_back(total->samples_ms[i]);
  return rounds;
}

}  // namespace

void BenchSession::run_interleaved(const std::vector<RunSpec>& runs, size_t begin, size_t end,
                                   const Progress& progress) {
  struct Slot {
    size_t index;
    std::optional<RunClaims::Claim> claim;
    std::unique_ptr<ActiveRun> active;
    RunResult result;
    std::string outcome;
    bool left_out = false;
  };
  std::vector<Slot> slots;
  for (size_t i = begin; i < end; ++i) {
    Slot& slot = slots.emplace_back();
    slot.index = i;
    slot.left_out = leave_out(runs[i], slot.claim, slot.outcome);
    if (slot.left_out) continue;
    std::fprintf(stderr, "%s", progress.start_text(i, runs[i]).c_str());
    slot.active = harness_.start(runs[i], slot.result);
    std::fprintf(stderr, "%s\n", slot.active ? ("warmed up (" + std::to_string(slot.active->result().warmup_frames) +
                                                  " frames), timed in rounds")
                                                     .c_str()
                                               : to_string(slot.result.status).c_str());
  }
  // Round-robin: each round gives every run its share while any run of the
  // block still wants frames (so each round's host conditions hold for all
  // of them), a run stopping only at its own cap (--frames N: N frames).
  const int least = std::max(1, options_.rounds);
  for (int round = 0;; ++round) {
    bool wanted = false;
    for (Slot& slot : slots) wanted |= slot.active && slot.active->wants_more();
    if (round >= least && !wanted) break;
    for (Slot& slot : slots) {
      if (!slot.active || slot.active->capped()) continue;
      const int per_round = std::max(1, (slot.active->result().spec.frames + least - 1) / least);
      if (!harness_.render_round(*slot.active, per_round, round)) {
        slot.result = std::move(slot.active->result());
        slot.active.reset();
      }
    }
  }
  for (Slot& slot : slots)
    if (slot.active) {
      slot.result = harness_.finish(*slot.active);
      slot.active.reset();
    }
  // The ratio to the block's baseline, paired by round.
  const Slot* base = nullptr;
  for (const Slot& slot : slots)
    if (!slot.left_out && slot.result.status == RunStatus::ok && slot.result.spec.technique == options_.baseline)
      base = &slot;
  if (base) {
    const auto base_rounds = samples_by_round(base->result);
    for (Slot& slot : slots)
      if (!slot.left_out && slot.result.status == RunStatus::ok) {
        slot.result.baseline = options_.baseline;
        slot.result.ratio = paired_round_ratio(samples_by_round(slot.result), base_rounds);
      }
  }
  for (Slot& slot : slots) {
    const std::string start = progress.start_text(slot.index, runs[slot.index]);
    images_.clear();
    if (!slot.left_out) slot.outcome = record(std::move(slot.result));
    std::fprintf(stderr, "%s%s\n", start.c_str(),
                 wrap_after(start.size(), slot.outcome + progress.timing_text(slot.index + 1)).c_str());
    if (!images_.empty()) std::fprintf(stderr, "  images: %s\n", images_.c_str());
  }
}

std::string BenchSession::record(RunResult result) {
  const std::string run_id = csv_.write(result, context_);
  if (samples_) samples_->append(result, run_id);
  if (json_) json_->add(result, run_id);
  std::string outcome;
  if (result.status == RunStatus::ok) {
    char text[64];
    std::snprintf(text, sizeof text, "%.2f ms, ", result.median_total_ms());
    outcome = text + error_text(result) + (result.noisy ? ", noisy" : "");
    if (result.clock_disagreement && *result.clock_disagreement > 0.10) {
      std::snprintf(text, sizeof text, "; warning: gl and wall clocks disagree by %.0f%% on total",
                    *result.clock_disagreement * 100.0);
      outcome += text;
    }
    images_ = write_images(result);
  } else {
    outcome = to_string(result.status) + ": " + result.message;
  }
  result.image = {};
  results_.push_back(std::move(result));
  return outcome;
}

std::string BenchSession::write_images(const RunResult& result) const {
  if (options_.images_dir.empty()) return "";
  const RunSpec& spec = result.spec;
  // Never over an earlier file: a name already there gets _2, _3, ...
  const std::string image = write_new_image(result.image, options_.images_dir + "/" + run_label(result) + ".png",
                                            parse_png_encoding(options_.png));
  std::string written = image;
  // Where the image is wrong, and how much, on the one scale of every error map.
  if (result.error && result.error->max_abs > 0.0) {
    const Image& reference =
        harness_.reference_image(spec.scene, spec.scene_params, spec.width, spec.height, spec.background, spec.camera);
    const std::string stem = image.substr(0, image.size() - 4);  // without ".png"
    written += " " + write_new_image(with_colour_bar(error_heatmap(result.image, reference), error_scale()),
                                     stem + "_error.png");
  }
  return written;
}

int BenchSession::report() const {
  size_t ok = 0, skipped = 0, failed = 0;
  for (const auto& r : results_)
    (r.status == RunStatus::ok ? ok : r.status == RunStatus::skipped ? skipped : failed) += 1;
  if (!results_.empty()) print_summary(results_, options_.baseline, builtin_techniques());
  // Lines naming the CSV are wrapped: its path may be long.
  const std::string& csv = options_.csv;
  auto runs_text = [](size_t n) { return std::to_string(n) + (n == 1 ? " run" : " runs"); };
  if (resumed_ > 0)
    std::printf("%s\n", wrap_after(0, "(" + runs_text(resumed_) + " already in " + csv +
                                          " from an earlier invocation: not in this table)").c_str());
  if (elsewhere_ > 0)
    std::printf("%s\n", wrap_after(0, "(" + runs_text(elsewhere_) + " left to another bench --resume on " + csv +
                                          ": not in this table)").c_str());
  const DeviceProfile& device = harness_.device();
  std::printf("\ndevice: %s\nplatform: %s\n%s\n", device.renderer.c_str(), platform_text(device).c_str(),
              wrap_after(0, "clock: " + clock_name(options_, harness_) + " | rows appended to " + csv).c_str());
  std::printf("runs: %zu done (%zu ok, %zu error), %zu resumed (already in the CSV), %zu skipped\n", ok + failed, ok,
              failed, resumed_, skipped);
  const ProgramCacheStats programs = ProgramCache::instance().stats();
  std::printf("GL programs: %llu compiled, %llu from the in-process binary cache%s\n",
              static_cast<unsigned long long>(programs.compiled), static_cast<unsigned long long>(programs.reused),
              ProgramCache::instance().enabled() ? "" : " (OIT_PROGRAM_CACHE=off)");
  // Every row is written; a sweep with failed runs still says so to scripts.
  if (failed == 0) return 0;
  std::fprintf(stderr, "oitbench bench: %zu run%s failed (error rows in %s)\n", failed, failed == 1 ? "" : "s",
               csv.c_str());
  return kExitRunsFailed;
}

}  // namespace

int run_bench(const CommonOptions& common, const BenchOptions& options) {
  // Every combination is checked before a context opens or a file is touched.
  expand_sweep(options.sweep, builtin_techniques());
  auto context = open_context(common);
  // Then expanded for the device: `auto` sizes and warm-up are its profile's.
  SweepOptions sweep = options.sweep;
  sweep.auto_size = context->device().default_size;
  sweep.auto_warmup_ms = context->device().default_warmup_ms;
  const std::vector<RunSpec> runs = expand_sweep(sweep, builtin_techniques());
  Harness harness(*context, builtin_techniques());
  if (const std::string warning = clock_warning(options.sweep.clock, harness.device()); !warning.empty())
    std::fprintf(stderr, "oitbench bench: %s\n", warning.c_str());
  BenchSession session(harness, options);
  const std::string header = "oitbench bench: " + std::to_string(runs.size()) + " runs on " +
                             harness.device().renderer + ", clock " + clock_name(options, harness) + " -> " +
                             options.csv +
                             (options.resume ? " (resuming: runs already there are not run again)" : "");
  // Wrapped like the progress lines: a long CSV path must not push it past the console width.
  std::fprintf(stderr, "%s\n", wrap_after(0, header).c_str());
  if (std::find(sweep.sizes.begin(), sweep.sizes.end(), "auto") != sweep.sizes.end())
    std::fprintf(stderr, "size auto: %s (this device's default)\n", sweep.auto_size.c_str());
  session.run_all(runs);
  return session.report();
}

}  // namespace oit
