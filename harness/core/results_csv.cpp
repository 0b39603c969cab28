#include "core/results_csv.h"

#include <csv.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
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
      "error_max", "error_rmse", "psnr", "ssim", "pixels_over_1_255",
      "other_cpu_load", "noisy", "clock_disagreement", "work_saved", "extra"};
  return columns;
}

std::string csv_escape(const std::string& field) {
  if (field.find_first_of(",\"\n\r") == std::string::npos) return field;
  std::string escaped = "\"";
  for (char c : field) escaped += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return escaped + "\"";
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

std::string header_line() {
  std::string line;
  for (const auto& column : csv_columns()) line += (line.empty() ? "" : ",") + column;
  return line;
}

std::runtime_error foreign_header(const std::string& path) {
  return std::runtime_error("CSV '" + path + "' exists with different columns; choose another --csv file");
}

// libcsv callbacks: a field ends, a record ends.
struct Records {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> current;
};
void end_field(void* text, size_t length, void* data) {
  auto& current = static_cast<Records*>(data)->current;
  current.push_back(length ? std::string(static_cast<const char*>(text), length) : std::string());
}
void end_record(int, void* data) {
  auto* records = static_cast<Records*>(data);
  records->rows.push_back(std::move(records->current));
  records->current.clear();
}
// Spaces around an unquoted field are data (libcsv trims them by default).
int no_space(unsigned char) { return 0; }

}  // namespace

std::vector<std::vector<std::string>> csv_rows(const RunResult& r, const RunContext& context) {
  const bool ran = r.status == RunStatus::ok;
  auto per_run = [&](const std::string& clock, const std::string& stage, const Summary* s) {
    std::vector<std::string> row = {
        context.timestamp, context.git_revision, context.device, context.gl_version, context.platform,
        r.spec.technique, r.technique_params, r.spec.scene, r.scene_params, r.spec.camera,
        std::to_string(r.spec.width), std::to_string(r.spec.height), r.spec.scene_rect ? "on" : "off", ran ? std::to_string(r.tiles) : "", clock, stage,
        s ? number(s->median) : "", s ? number(s->min) : "", s ? number(s->p05) : "", s ? number(s->p95) : "",
        s ? number(s->mean) : "", s ? std::to_string(s->count) : "", std::to_string(r.spec.warmup),
        to_string(r.status), r.message,
        ran ? std::to_string(r.scene_fragments) : "", ran ? std::to_string(r.max_depth_complexity) : "",
        ran ? number(r.mean_depth_complexity) : "", ran ? number(r.psi) : "",
        ran ? std::to_string(r.counters.bytes_allocated) : "", ran ? std::to_string(r.counters.fragments_stored) : "",
        ran ? std::to_string(r.counters.fragments_dropped) : "", ran ? std::to_string(r.counters.passes) : "",
        ran ? std::to_string(r.counters.overflow_retries) : "",
        r.error ? number(r.error->max_abs) : "", r.error ? number(r.error->rmse) : "",
        r.error ? number(r.error->psnr_db) : "", r.error ? number(r.error->ssim) : "",
        r.error ? number(r.error->share_over_1_255) : "",
        r.other_process_load >= 0.0 ? number(r.other_process_load) : "", r.noisy ? "true" : "false",
        r.clock_disagreement ? number(*r.clock_disagreement) : "", ran ? extra_text(r.counters.work_saved) : "",
        ran ? extra_text(r.counters.extra) : ""};
    return row;
  };
  std::vector<std::vector<std::string>> rows;
  if (!ran || r.stages.empty()) {
    rows.push_back(per_run(to_string(r.clock), "", nullptr));
    return rows;
  }
  for (const auto& stage : r.stages) rows.push_back(per_run(stage.clock, stage.stage, &stage.summary));
  return rows;
}

CsvWriter::CsvWriter(const std::string& path) : path_(path) {
  const std::filesystem::path file(path);
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  bool write_header = true;
  if (std::filesystem::exists(file) && std::filesystem::file_size(file) > 0) {
    std::ifstream existing(path);
    std::string first;
    std::getline(existing, first);
    if (first != header_line()) throw foreign_header(path);
    write_header = false;
  }
  out_.open(path, std::ios::app);
  if (!out_) throw std::runtime_error("cannot open CSV '" + path + "' for appending");
  if (write_header) out_ << header_line() << "\n" << std::flush;
}

void CsvWriter::write(const RunResult& result, const RunContext& context) {
  for (const auto& row : csv_rows(result, context)) {
    std::string line;
    for (size_t i = 0; i < row.size(); ++i) line += (i ? "," : "") + csv_escape(row[i]);
    out_ << line << "\n";
  }
  out_.flush();
  if (!out_) throw std::runtime_error("failed writing CSV '" + path_ + "'");
}

std::vector<std::vector<std::string>> read_csv(const std::string& path) {
  if (!std::filesystem::exists(path) || std::filesystem::file_size(path) == 0) return {};
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read CSV '" + path + "'");
  csv_parser parser;
  if (csv_init(&parser, 0) != 0) throw std::runtime_error("cannot read CSV '" + path + "': libcsv init failed");
  csv_set_space_func(&parser, no_space);
  Records records;
  char block[1 << 16];
  bool failed = false;
  while (!failed && in) {
    in.read(block, sizeof block);
    const size_t got = static_cast<size_t>(in.gcount());
    failed = csv_parse(&parser, block, got, end_field, end_record, &records) != got;
  }
  failed = failed || csv_fini(&parser, end_field, end_record, &records) != 0;
  const std::string why = failed ? csv_strerror(csv_error(&parser)) : "";
  csv_free(&parser);
  if (failed) throw std::runtime_error("cannot read CSV '" + path + "': " + why);
  return records.rows;
}

std::set<RunKey> finished_runs(const std::string& path) {
  const auto rows = read_csv(path);
  std::set<RunKey> finished;
  if (rows.empty()) return finished;
  if (rows.front() != csv_columns()) throw foreign_header(path);
  auto at = [](const std::string& name) {
    const auto& columns = csv_columns();
    return size_t(std::find(columns.begin(), columns.end(), name) - columns.begin());
  };
  const size_t technique = at("technique"), params = at("params"), scene = at("scene"),
               scene_params = at("scene_params"), camera = at("camera"), width = at("width"), height = at("height"),
               status = at("status"), scene_rect = at("scene_rect");
  for (size_t i = 1; i < rows.size(); ++i) {
    const auto& row = rows[i];
    if (row.size() != csv_columns().size() || (row[status] != "ok" && row[status] != "skipped")) continue;
    try {
      finished.insert({row[technique], row[params], row[scene], row[scene_params], row[camera], std::stoi(row[width]),
                       std::stoi(row[height]), row[scene_rect] != "off"});
    } catch (const std::exception&) {
      // A size that is not a number is no row of ours: nothing to resume.
    }
  }
  return finished;
}

}  // namespace oit
