#pragma once
// Long-form CSV: one row per run x stage x clock, plus per-run columns
// repeated on each row so that every row stands alone in pandas.
#include <fstream>
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

}  // namespace oit
