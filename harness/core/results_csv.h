#pragma once
// Long-form CSV: one row per run x stage x clock, plus per-run columns
// repeated on each row so that every row stands alone in pandas.
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "core/runner.h"

namespace oit {

const std::vector<std::string>& csv_columns();

struct RunContext {
  std::string device;       // GL_RENDERER
  std::string gl_version;   // GL_VERSION
  std::string platform;     // egl-device / egl-surfaceless
  std::string git_revision;
  std::string timestamp;    // ISO 8601 UTC of the sweep start
};

// Appends rows to `path`, writing the header first when the file is new or
// empty, and flushing after every run so that nothing is lost on a crash.
// Throws naming the path when an existing file has a different header.
class CsvWriter {
 public:
  explicit CsvWriter(const std::string& path);
  void write(const RunResult& result, const RunContext& context);

 private:
  std::string path_;
  std::ofstream out_;
};

std::vector<std::vector<std::string>> csv_rows(const RunResult& result, const RunContext& context);
std::string csv_escape(const std::string& field);
std::string utc_timestamp();

// Every record of a CSV file, header first, read with Debian's libcsv
// (RFC 4180: quoted fields may hold commas, doubled quotes and newlines;
// no trimming). A missing or empty file has none. Throws naming the path.
std::vector<std::vector<std::string>> read_csv(const std::string& path);

// What tells runs apart across invocations of a sweep: technique, canonical
// parameters, scene, canonical scene parameters, camera, size (the key of
// analysis/reproduce.py's resume too, which never turns the scene rectangle
// off), and whether the harness's scene rectangle was on.
struct RunKey {
  std::string technique, params, scene, scene_params, camera;
  int width = 0, height = 0;
  bool scene_rect = true;
  auto operator<=>(const RunKey&) const = default;
};

// The runs that have an `ok` or `skipped` row in a results CSV (an `error`
// run is not finished: it is run again). None when the file is missing or
// empty; throws like CsvWriter when its header is not ours. Rows cut short
// (a crash while writing) are ignored.
std::set<RunKey> finished_runs(const std::string& path);

}  // namespace oit
