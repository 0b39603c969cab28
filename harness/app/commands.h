#pragma once
#include <string>
#include <vector>

#include "harness/app/sweep.h"
#include "harness/run/results_csv.h"

namespace oit {

// Exit codes: 0 every run ok or skipped; 1 a bad value or an error outside
// the runs (an unreadable or foreign file; CLI11's value errors included); 2
// a malformed command line (an unknown command or option, a missing --csv);
// 3 stress, check-order or doctor found a failure (check-order's error
// verdicts too); 4 bench, pareto, adaptive or gbench wrote every row but
// some runs are error rows.
inline constexpr int kExitRunsFailed = 4;

// The CSV's `platform` column and the `Device:` lines: how the context was
// made, the page policy of the host heap (huge_page_malloc.h), which on
// software GL holds every GL buffer, and whether shared counters take the
// subgroup path (gl/shader_capabilities.h): both change timings.
std::string platform_text(const DeviceProfile& device);
// The per-sweep columns of every CSV row (device, revision, start time).
RunContext run_context(const DeviceProfile& device);

struct CommonOptions {
  std::string device = "auto";
  bool debug_gl = false;
};

struct RenderOptions {
  std::string technique = "reference";
  std::vector<std::string> sets;
  std::string scene = "quads";
  std::vector<std::string> scene_sets;
  std::string size = kDefaultSize;
  std::string out;
  std::string background = "0,0,0";
  // One camera spec; a random:N:SEED set writes one image per viewpoint
  // (OUT with _camI before the extension).
  std::string camera = "default";
  std::string scene_rect = "on";  // RunSpec::scene_rect
  std::string memory_budget;      // RunSpec::memory_budget; empty: the device's default
  std::string png = "display";    // parse_png_encoding (harness/output/image.h)
};

// `oitbench stats`: the fragment statistics of one scene view (stats_command.cpp).
struct StatsOptions {
  std::string scene = "quads";
  std::vector<std::string> scene_sets;
  std::string camera = "default";  // a random set prints every viewpoint
  std::string size = kDefaultSize;
  std::string heatmap;             // list-length heatmap PNG (one per viewpoint, _camI, for a set)
};

struct BenchOptions {
  SweepOptions sweep;
  std::string csv;
  std::string images_dir;  // one PNG per run when set
  std::string png = "display";  // their encoding (parse_png_encoding); error heatmaps are always display
  std::string baseline = "unsorted";  // the summary's speed ratios are against this technique
  std::string samples;  // bench_files.h: every frame's stage times, when set
  std::string json;     // bench_files.h: this invocation's runs as JSON, when set
  // Leave out every run that already has an ok or skipped row in `csv`.
  bool resume = false;
  // The runs of one block (scene, its parameters, camera, size, scene
  // rectangle: the runs the summary compares) are kept alive together and
  // their timed frames run in interleaved rounds, round-robin (A B C, A B C,
  // ...), so that a slow spell of the host hits each alike; the ratio to the
  // baseline is then paired by round. 1: each run whole, one after another.
  int rounds = 6;
};

// `oitbench export --wide RESULTS.csv -o OUT.csv` (export_command.cpp): one
// row per whole run: the CSV's per-run columns, then param.<name> per
// technique parameter, scene.<name> per scene parameter, extra.<name> and
// work_saved.<name> per figure, and <stage>.<clock>.<median|min|p05|p95|mean>_ms
// per stage and clock; empty where a run has no such value. Incomplete
// runs are left out and named on stderr.
struct ExportOptions {
  std::string wide;
  std::string out;
};
int run_export(const ExportOptions& options);
// `oitbench compare ...`: /usr/bin/python3 -m analysis.compare with the
// same arguments (compare_command.cpp); returns only when it cannot start.
int run_compare(const std::vector<std::string>& arguments);

int run_list(const CommonOptions& common);
// The README's technique table, generated from the registry (`oitbench list
// --markdown` prints it; a test holds the README to it): one row per
// technique with its paper, kind, parameters (default and range) and stages.
std::string technique_table_markdown(const TechniqueRegistry& registry);
// A technique README's parameter table, generated from its descriptor
// (`oitbench list --markdown --params ID` prints it; a test holds every
// technique README to it): one row per parameter with its default, range
// and description, so that each parameter is described once, in the registry.
std::string technique_params_markdown(const TechniqueDescriptor& technique);
int run_render(const CommonOptions& common, const RenderOptions& options);
int run_bench(const CommonOptions& common, const BenchOptions& options);
int run_stats(const CommonOptions& common, const StatsOptions& options);

// OUT with "_cam<index>" before its extension: one file per viewpoint of a set.
std::string per_view_path(const std::string& out, size_t index);

}  // namespace oit
