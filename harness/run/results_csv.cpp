#include "harness/run/results_csv.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <functional>
#include <map>
#include <random>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace oit {

const std::vector<std::string>& csv_columns() {
  static const std::vector<std::string> columns = {
      "timestamp", "git_revision", "device", "gl_version", "platform",
      "technique", "params", "scene", "scene_params", "camera", "width", "height", "scene_rect", "tiles",
      "clock", "stage", "median_ms", "min_ms", "p05_ms", "p95_ms", "mean_ms", "frames", "warmup",
      "status", "message",
      "fragments", "max_depth_complexity", "mean_depth_complexity", "psi",
      "bytes_allocated", "fragments_stored", "fragments_dropped", "passes", "overflow_retries",
      "error_max", "error_rmse", "psnr", "ssim", "flip", "pixels_over_1_255",
      "other_cpu_load", "noisy", "clock_disagreement", "work_saved", "extra", "run_id", "run_rows",
      // Added after run_rows so that every earlier column keeps its place.
      "requested_params", "ci_low_ms", "ci_high_ms", "precision_reached", "rounds", "baseline", "ratio",
      "ratio_ci_low", "ratio_ci_high", "warnings", "frame_overhead_ms", "gpu_sm_mhz_start", "gpu_sm_mhz_end",
      "gpu_mem_mhz_start", "gpu_mem_mhz_end", "gpu_temp_c_end", "samples_ms"};
  return columns;
}

std::string utc_timestamp() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

namespace {

std::string number(double value) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return text;
}

std::string extra_text(const std::vector<Figure>& extra) {
  std::string text;
  // Ten significant digits: counts such as a scene's triangles stay exact
  // (six would print 1234567 as 1.23457e+06).
  for (const auto& [name, value, combine] : extra) {
    char formatted[64];
    std::snprintf(formatted, sizeof(formatted), "%.10g", value);
    text += (text.empty() ? "" : " ") + name + "=" + formatted;
  }
  return text;
}

size_t column(const std::string& name) {
  const auto& columns = csv_columns();
  return size_t(std::find(columns.begin(), columns.end(), name) - columns.begin());
}

std::runtime_error foreign_header(const std::string& path) {
  return std::runtime_error("results CSV '" + path + "' exists with different columns; choose another file");
}

// The run_rows a well-formed row declares; 0 for a row that is not one.
size_t declared_rows(const CsvRecord& row) {
  if (row.fields.size() != csv_columns().size() || row.fields[column("run_id")].empty()) return 0;
  const std::string& text = row.fields[column("run_rows")];
  size_t value = 0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size() ? value : 0;
}

std::string run_id_of(const CsvRecord& row) {
  return row.fields.size() > column("run_id") ? row.fields[column("run_id")] : std::string();
}

// How many leading rows form whole runs: the rows of the last run_id at the
// end are cut unless all of them are there (an append cut short by a crash).
size_t whole_runs_prefix(const std::vector<CsvRecord>& rows) {
  if (rows.empty()) return 0;
  const std::string last = run_id_of(rows.back());
  size_t begin = rows.size();
  while (begin > 0 && run_id_of(rows[begin - 1]) == last) --begin;
  const size_t count = rows.size() - begin;
  for (size_t i = begin; i < rows.size(); ++i)
    if (declared_rows(rows[i]) != count) return begin;
  return rows.size();
}

}  // namespace

std::vector<std::vector<std::string>> csv_rows(const RunResult& r, const RunContext& context,
                                               const std::string& run_id) {
  const bool ran = r.status == RunStatus::ok;
  auto per_run = [&](const std::string& clock, const std::string& stage, const Summary* s) {
    std::vector<std::string> row = {
        context.timestamp, context.git_revision, context.device, context.gl_version, context.platform,
        r.spec.technique, r.technique_params, r.spec.scene, r.scene_params, r.spec.camera,
        std::to_string(r.spec.width), std::to_string(r.spec.height), r.spec.scene_rect ? "on" : "off", ran ? std::to_string(r.tiles) : "", clock, stage,
        s ? number(s->median) : "", s ? number(s->min) : "", s ? number(s->p05) : "", s ? number(s->p95) : "",
        s ? number(s->mean) : "", s ? std::to_string(s->count) : "", std::to_string(ran ? r.warmup_frames : r.spec.warmup),
        to_string(r.status), r.message,
        ran ? std::to_string(r.scene_fragments) : "", ran ? std::to_string(r.max_depth_complexity) : "",
        ran ? number(r.mean_depth_complexity) : "", ran ? number(r.psi) : "",
        ran ? std::to_string(r.counters.bytes_allocated) : "", ran ? std::to_string(r.counters.fragments_stored) : "",
        ran ? std::to_string(r.counters.fragments_dropped) : "", ran ? std::to_string(r.counters.passes) : "",
        ran ? std::to_string(r.counters.overflow_retries) : "",
        r.error ? number(r.error->max_abs) : "", r.error ? number(r.error->rmse) : "",
        r.error ? number(r.error->psnr_db) : "", r.error ? number(r.error->ssim) : "",
        r.error ? number(r.error->flip) : "",
        r.error ? number(r.error->share_over_1_255) : "",
        r.other_process_load >= 0.0 ? number(r.other_process_load) : "", r.noisy ? "true" : "false",
        r.clock_disagreement ? number(*r.clock_disagreement) : "", ran ? extra_text(r.counters.work_saved) : "",
        ran ? extra_text(r.counters.extra) : ""};
    return row;
  };
  std::vector<std::vector<std::string>> rows;
  std::vector<const StageResult*> stages;
  if (!ran || r.stages.empty()) {
    rows.push_back(per_run(to_string(r.clock), "", nullptr));
    stages.push_back(nullptr);
  } else {
    for (const auto& stage : r.stages) {
      rows.push_back(per_run(stage.clock, stage.stage, &stage.summary));
      stages.push_back(&stage);
    }
  }
  for (size_t i = 0; i < rows.size(); ++i) {
    std::vector<std::string>& row = rows[i];
    row.push_back(run_id);
    row.push_back(std::to_string(rows.size()));
    const StageResult* stage = stages[i];
    const auto clock = [&](bool end, unsigned GpuClockReading::*field) {
      const auto& reading = end ? r.gpu_end : r.gpu_start;
      return reading ? std::to_string((*reading).*field) : std::string();
    };
    std::string warnings, samples;
    for (const auto& warning : r.warnings) warnings += (warnings.empty() ? "" : "; ") + warning;
    if (stage)
      for (double ms : stage->samples_ms) samples += (samples.empty() ? "" : " ") + number(ms);
    const bool measured = ran && stage;
    const std::vector<std::string> added = {
        // A run that never got to its resolution asked for what it names.
        r.requested_params.empty() ? r.technique_params : r.requested_params,
        measured ? number(stage->summary.interval.low) : "",
        measured ? number(stage->summary.interval.high) : "",
        ran && r.spec.precision > 0.0 ? (r.precision_reached ? "true" : "false") : "",
        ran ? std::to_string(r.rounds) : "",
        r.ratio ? r.baseline : "",
        r.ratio ? number(r.ratio->ratio) : "",
        r.ratio ? number(r.ratio->interval.low) : "",
        r.ratio ? number(r.ratio->interval.high) : "",
        warnings,
        r.frame_overhead_ms ? number(*r.frame_overhead_ms) : "",
        clock(false, &GpuClockReading::sm_mhz),
        clock(true, &GpuClockReading::sm_mhz),
        clock(false, &GpuClockReading::memory_mhz),
        clock(true, &GpuClockReading::memory_mhz),
        clock(true, &GpuClockReading::temperature_c),
        samples};
    row.insert(row.end(), added.begin(), added.end());
  }
  return rows;
}

std::string new_run_id() {
  static const std::string prefix = [] {
    std::random_device random;
    char text[32];
    std::snprintf(text, sizeof text, "%08x%04x", random(), random() & 0xffffu);
    return std::string(text);
  }();
  static std::atomic<uint64_t> counter{0};
  return prefix + "-" + std::to_string(++counter);
}

CsvWriter::CsvWriter(const std::string& path) : csv_(path, csv_columns(), "results CSV", "run", whole_runs_prefix) {
  oit::finished_runs(csv_.read(), path, &problems_);
  for (const auto& problem : problems_)
    std::fprintf(stderr, "oitbench: results CSV '%s', %s: not counted as a run\n", path.c_str(), problem.c_str());
}

std::string CsvWriter::write(const RunResult& result, const RunContext& context) {
  const std::string run_id = new_run_id();
  csv_.append(csv_rows(result, context, run_id));
  return run_id;
}

std::set<RunKey> CsvWriter::finished_runs() const { return oit::finished_runs(csv_.read(), path()); }

std::set<RunKey> finished_runs(const std::string& path) {
  return finished_runs(read_csv_file(path, "results CSV"), path);
}

std::vector<CsvRun> whole_runs(const CsvContents& contents, const std::string& path,
                               std::vector<std::string>* problems) {
  std::vector<std::string> found;
  if (contents.records.empty() && !contents.torn) return {};
  if (contents.records.empty() || contents.records.front().fields != csv_columns()) throw foreign_header(path);
  // Rows grouped by run (in the order of their first rows): a run counts once all its rows are there.
  struct Run {
    size_t declared = 0;
    CsvRun rows;
  };
  std::vector<Run> runs;
  std::map<std::string, size_t> index;
  for (size_t i = 1; i < contents.records.size(); ++i) {
    const CsvRecord& row = contents.records[i];
    if (row.fields.size() != csv_columns().size()) continue;  // field_count_problems reports it
    const auto [at, added] = index.emplace(row.fields[column("run_id")], runs.size());
    if (added) runs.push_back({declared_rows(row), {}});
    Run& run = runs[at->second];
    run.rows.push_back(&row);
    if (declared_rows(row) != run.declared) run.declared = 0;
  }
  found = field_count_problems(contents);
  if (contents.torn) found.push_back("line " + std::to_string(contents.torn->line) + ": cut short (no final newline)");
  std::vector<CsvRun> whole;
  for (const Run& run : runs) {
    if (run.declared != 0 && run.rows.size() == run.declared) {
      whole.push_back(run.rows);
      continue;
    }
    found.push_back("line " + std::to_string(run.rows.front()->line) + ": run '" + run_id_of(*run.rows.front()) +
                    "' has " + std::to_string(run.rows.size()) + " row(s)" +
                    (run.declared ? " of " + std::to_string(run.declared) : " without a valid run_rows"));
  }
  if (problems) *problems = std::move(found);
  return whole;
}

std::vector<std::pair<std::string, std::string>> csv_pairs(const std::string& text) {
  std::vector<std::pair<std::string, std::string>> pairs;
  std::istringstream in(text);
  std::string word;
  while (in >> word) {
    const auto eq = word.find('=');
    pairs.emplace_back(word.substr(0, eq), eq == std::string::npos ? "" : word.substr(eq + 1));
  }
  return pairs;
}

size_t csv_column(const std::string& name) {
  const size_t index = column(name);
  if (index == csv_columns().size()) throw std::logic_error("the results CSV has no column '" + name + "'");
  return index;
}

std::set<RunKey> finished_runs(const CsvContents& contents, const std::string& path,
                               std::vector<std::string>* problems) {
  std::set<RunKey> finished;
  for (const CsvRun& run : whole_runs(contents, path, problems)) {
    const auto& f = run.front()->fields;
    if (f[column("status")] != "ok" && f[column("status")] != "skipped") continue;
    try {
      // The parameters as asked for: a resumed sweep asks again for the same.
      finished.insert({f[column("technique")], f[column("requested_params")], f[column("scene")], f[column("scene_params")],
                       f[column("camera")], std::stoi(f[column("width")]), std::stoi(f[column("height")]),
                       f[column("scene_rect")] != "off"});
    } catch (const std::exception&) {
      if (problems)
        problems->push_back("line " + std::to_string(run.front()->line) + ": width or height is not a number");
    }
  }
  return finished;
}

RunClaims::RunClaims(const std::string& csv_path) : path_(csv_path + ".claims") {
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NONBLOCK, 0666);
  if (fd_ < 0) throw std::runtime_error("cannot open the claims file '" + path_ + "': " + std::strerror(errno));
  struct stat info{};
  if (::fstat(fd_, &info) != 0 || !S_ISREG(info.st_mode)) {
    ::close(fd_);
    throw std::runtime_error("the claims file '" + path_ + "' is not a regular file");
  }
}

RunClaims::~RunClaims() { ::close(fd_); }

namespace {
struct flock claim_range(short type, int64_t offset) {
  struct flock range{};
  range.l_type = type;
  range.l_whence = SEEK_SET;
  range.l_start = offset;
  range.l_len = 1;
  return range;
}
}  // namespace

std::optional<RunClaims::Claim> RunClaims::try_claim(const RunKey& key) {
  const std::string text = key.technique + '\x1f' + key.params + '\x1f' + key.scene + '\x1f' + key.scene_params +
                           '\x1f' + key.camera + '\x1f' + std::to_string(key.width) + 'x' +
                           std::to_string(key.height) + (key.scene_rect ? "" : "\x1foff");
  // A byte of the file per run (the lock, not the byte, is the claim);
  // libstdc++'s string hash is fixed, so every process finds the same byte.
  const int64_t offset = int64_t(std::hash<std::string>{}(text) & ((uint64_t(1) << 62) - 1));
  struct flock range = claim_range(F_WRLCK, offset);
  while (::fcntl(fd_, F_OFD_SETLK, &range) != 0) {
    if (errno == EAGAIN || errno == EACCES) return std::nullopt;
    if (errno != EINTR)
      throw std::runtime_error("cannot lock the claims file '" + path_ + "': " + std::strerror(errno));
  }
  return Claim(fd_, offset);
}

RunClaims::Claim::~Claim() {
  if (fd_ < 0) return;
  struct flock range = claim_range(F_UNLCK, offset_);
  ::fcntl(fd_, F_OFD_SETLK, &range);
}

}  // namespace oit
