#include "harness/app/bench_report.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstdio>
#include <map>
#include <sstream>

#include "harness/app/sweep.h"
#include "harness/run/results_csv.h"
#include "harness/run/system_load.h"
#include "scenes/scene_library.h"

namespace oit {
namespace {

// The canonical entries that differ from the default or that the user named
// (a swept k=16,32 shows k=16 although 16 is the default).
std::string label_params(const ParamSchema& schema, const std::string& canonical, const RawParams& given) {
  std::map<std::string, std::string> defaults;
  for (const auto& [key, value] : csv_pairs(ParamSet(schema, {}, "defaults").canonical())) defaults[key] = value;
  std::string label;
  for (const auto& [key, value] : csv_pairs(canonical))
    if (given.count(key) || defaults[key] != value) label += (label.empty() ? "" : " ") + key + "=" + value;
  return label;
}

const ParamSchema* technique_schema(const TechniqueRegistry& registry, const std::string& id) {
  for (const auto& technique : registry.all())
    if (technique.id == id) return &technique.params;
  return nullptr;
}

const ParamSchema* scene_schema(const std::string& scene) {
  for (const auto& descriptor : scene_library())
    if (descriptor.id == scene) return &descriptor.params;
  return nullptr;
}

std::string scene_label(const RunResult& r) {
  const ParamSchema* schema = scene_schema(r.spec.scene);
  const std::string params = schema ? label_params(*schema, r.scene_params, r.spec.scene_params) : "";
  return r.spec.scene + (params.empty() ? "" : " " + params);
}

// The runs that share scene, scene parameters, camera, size and scene
// rectangle: the ratio column compares within one block only.
std::string block_title(const RunResult& r) {
  return scene_label(r) + ", " + std::to_string(r.spec.width) + "x" + std::to_string(r.spec.height) +
         (r.spec.camera == "default" ? "" : ", camera " + r.spec.camera) + (r.spec.scene_rect ? "" : ", scene_rect off");
}

std::vector<std::vector<const RunResult*>> blocks_in_sweep_order(const std::vector<RunResult>& results) {
  std::vector<std::string> titles;
  std::vector<std::vector<const RunResult*>> blocks;
  for (const auto& r : results) {
    const std::string title = block_title(r);
    const auto at = std::find(titles.begin(), titles.end(), title);
    if (at == titles.end()) {
      titles.push_back(title);
      blocks.push_back({&r});
    } else {
      blocks[size_t(at - titles.begin())].push_back(&r);
    }
  }
  // Fastest first; skipped and error runs (no time) after the ok ones, in sweep order.
  for (auto& block : blocks)
    std::stable_sort(block.begin(), block.end(), [](const RunResult* a, const RunResult* b) {
      const bool a_ok = a->status == RunStatus::ok, b_ok = b->status == RunStatus::ok;
      if (a_ok != b_ok) return a_ok;
      return a_ok && a->median_total_ms() < b->median_total_ms();
    });
  return blocks;
}

double block_base(const std::vector<const RunResult*>& block, const std::string& baseline) {
  for (const RunResult* r : block)
    if (r->status == RunStatus::ok && (baseline.empty() || r->spec.technique == baseline)) return r->median_total_ms();
  return 0.0;
}

std::string number(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

// "12.77±0.31": the median total and the half-width of its 95% interval.
std::string median_text(const RunResult& r) {
  const StageResult* total = r.total();
  if (!total) return "";
  const Summary& s = total->summary;
  return number("%.2f", s.median) + "±" + number("%.2g", (s.interval.high - s.interval.low) / 2.0);
}

// The ratio to the baseline: paired by round with its 95% interval where the
// runs were interleaved, else the plain ratio of the medians.
std::string ratio_text(const RunResult& r, double base) {
  if (r.ratio)
    return number("%.2f", r.ratio->ratio) + " [" + number("%.2f", r.ratio->interval.low) + "-" +
           number("%.2f", r.ratio->interval.high) + "]";
  return base > 0.0 ? number("%.2f", r.median_total_ms() / base) : "";
}

void print_row(const RunResult& r, const std::string& params, double base) {
  const std::string status = to_string(r.status);
  if (r.status != RunStatus::ok) {
    // Nothing measured: the reason where the figures would be.
    std::printf("%-26s %-20s %-7s %s\n", fit(r.spec.technique, 26).c_str(), fit(params, 20).c_str(), status.c_str(),
                fit(r.message, kConsoleWidth - 56).c_str());
    return;
  }
  const std::string error = r.error ? number("%.3g", r.error->max_abs) : "";
  char row[256];
  std::snprintf(row, sizeof row, "%-26s %-20s %-7s %14s %20s %9s %9llu %s", fit(r.spec.technique, 26).c_str(),
                fit(params, 20).c_str(), status.c_str(), median_text(r).c_str(), ratio_text(r, base).c_str(),
                error.c_str(), static_cast<unsigned long long>(r.counters.fragments_dropped), r.noisy ? "yes" : "");
  std::string line = row;
  line.erase(line.find_last_not_of(' ') + 1);
  std::printf("%s\n", line.c_str());
  // Cut to its column, a parameter text may lose what tells two rows apart.
  if (params.size() > 20) std::printf("    %s\n", wrap_after(4, "params: " + params).c_str());
  // Figures that saved nothing (0) say nothing worth a line.
  std::string saved;
  for (const Figure& figure : r.counters.work_saved)
    if (figure.value != 0.0) saved += " " + figure.name + "=" + number("%.10g", figure.value);
  if (!saved.empty()) std::printf("%s\n", fit("    work saved:" + saved, kConsoleWidth).c_str());
  for (const std::string& warning : r.warnings) std::printf("    %s\n", wrap_after(4, "warning: " + warning).c_str());
  if (r.spec.precision > 0.0 && !r.precision_reached)
    std::printf("    %s\n", wrap_after(4, "precision " + number("%.3g", r.spec.precision) + " not reached after " +
                                            std::to_string(r.total() ? r.total()->summary.count : 0) +
                                            " frames (a cap stopped it)").c_str());
}

}  // namespace

std::string non_default_params(const ParamSchema& schema, const std::string& canonical) {
  return label_params(schema, canonical, {});
}

std::string fit(const std::string& text, size_t width) {
  if (text.size() <= width) return text;
  return width < 3 ? text.substr(0, width) : text.substr(0, width - 3) + "...";
}

namespace {

// Appends the words of `text` to `out`, whose last line holds `column`
// columns, breaking before a word that would pass `width` (a longer word
// stays whole) onto a line indented by `indent` spaces.
void append_wrapped(std::string& out, const std::string& text, size_t column, size_t width, size_t indent) {
  std::istringstream words(text);
  bool first = true;
  for (std::string word; words >> word; first = false) {
    if (!first && column + 1 + word.size() > width) {
      out += "\n" + std::string(indent, ' ');
      column = indent;
    } else if (!first) {
      out += ' ';
      column += 1;
    }
    out += word;
    column += word.size();
  }
}

}  // namespace

std::string wrap_after(size_t column, const std::string& text) {
  std::string wrapped;
  append_wrapped(wrapped, text, column, kConsoleWidth, 4);
  return wrapped;
}

std::string wrap_text(const std::string& text, size_t width, size_t indent) {
  std::string wrapped;
  std::istringstream lines(text);
  bool first_line = true;
  for (std::string line; std::getline(lines, line); first_line = false) {
    if (!first_line) wrapped += '\n';
    // Leading spaces are the line's own indentation: kept.
    const size_t lead = std::min(line.find_first_not_of(' '), line.size());
    wrapped += line.substr(0, lead);
    append_wrapped(wrapped, line.substr(lead), lead, width, indent);
  }
  return wrapped;
}

size_t terminal_width() {
  if (const char* columns = std::getenv("COLUMNS")) {
    char* end = nullptr;
    const long value = std::strtol(columns, &end, 10);
    if (end != columns && *end == '\0' && value >= 20 && value <= 10000) return size_t(value);
  }
  winsize size{};
  if (isatty(STDOUT_FILENO) && ioctl(STDOUT_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col >= 20) return size.ws_col;
  return kConsoleWidth;
}

std::string clock_text(double seconds) {
  const long total = long(seconds + 0.5);
  char text[32];
  if (total >= 3600) std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", total / 3600, total / 60 % 60, total % 60);
  else std::snprintf(text, sizeof text, "%ld:%02ld", total / 60, total % 60);
  return text;
}

Progress::Progress(size_t runs, Clock clock) : runs_(runs), clock_(std::move(clock)), start_(clock_()) {}

std::string Progress::start_text(size_t index, const RunSpec& spec) const {
  const std::string text = "[" + std::to_string(index + 1) + "/" + std::to_string(runs_) + "] " +
                           run_name(spec, {" ", "=", " on ", " camera ", " scene_rect off"});
  // Room for the outcome on the same line.
  return fit(text, kConsoleWidth - 40) + " ... ";
}

std::string Progress::Timing::text() const {
  const double elapsed = std::chrono::duration<double>(progress_.clock_() - progress_.start_).count();
  const size_t runs = progress_.runs_;
  std::string text = " [elapsed " + clock_text(elapsed);
  if (done_ > 0 && done_ < runs) text += ", ETA " + clock_text(elapsed / double(done_) * double(runs - done_));
  return text + "]";
}

void print_summary(const std::vector<RunResult>& results, const std::string& baseline,
                   const TechniqueRegistry& registry) {
  const auto blocks = blocks_in_sweep_order(results);
  bool has_baseline = false;
  for (const auto& block : blocks) has_baseline |= block_base(block, baseline) > 0.0;
  const std::string ratio = has_baseline ? "x " + baseline : "x fastest";
  std::printf("\n%-26s %-20s %-7s %14s %20s %9s %9s %-5s\n", "technique", "params", "status", "median±95% ms",
              fit(ratio + " [95%]", 20).c_str(), "max error", "dropped", "noisy");
  for (const auto& block : blocks) {
    std::printf("%s\n", fit("-- " + block_title(*block.front()), kConsoleWidth).c_str());
    const double base = block_base(block, has_baseline ? baseline : "");
    for (const RunResult* r : block) {
      const ParamSchema* schema = technique_schema(registry, r->spec.technique);
      print_row(*r, schema ? label_params(*schema, r->technique_params, r->spec.params) : "", base);
    }
  }
  std::printf("%s\n", fit(has_baseline ? "(" + ratio + ": median total over " + baseline +
                                             "'s in the same block, paired by round; params: as run, non-default)"
                                       : "(" + ratio + ": " + baseline +
                                             " did not run ok here, so ratios are over each block's fastest run)",
                          kConsoleWidth)
                          .c_str());
  std::printf("(median±: the median per-frame total time and the half-width of its 95%% interval)\n");
  std::printf("(noisy: other processes used over %.0f%% of the cores, or the GPU's clock moved)\n",
              kNoisyLoadThreshold * 100.0);
  for (const RunResult& r : results)
    if (r.frame_overhead_ms) {
      std::printf("(frame overhead floor: %.3g ms on the %s clock, the median empty frame; a total under 5x it is "
                  "mostly fixed cost)\n",
                  *r.frame_overhead_ms, to_string(r.clock).c_str());
      break;
    }
}

}  // namespace oit
