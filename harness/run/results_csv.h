#pragma once
// Long-form CSV: one row per run x stage x clock, plus per-run columns
// repeated on each row so that every row stands alone in pandas.
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "harness/output/csv_file.h"
#include "harness/run/runner.h"

namespace oit {

const std::vector<std::string>& csv_columns();

struct RunContext {
  std::string device;       // GL_RENDERER
  std::string gl_version;   // GL_VERSION
  std::string platform;     // egl-device / egl-surfaceless
  std::string git_revision;
  std::string timestamp;    // ISO 8601 UTC of the sweep start
};

// What tells runs apart across invocations of a sweep: technique, canonical
// parameters as requested (requested_params: auto stays auto), scene, canonical scene parameters, camera, size (the key of
// analysis/reproduce.py's resume too, which never turns the scene rectangle
// off), and whether the harness's scene rectangle was on.
struct RunKey {
  std::string technique, params, scene, scene_params, camera;
  int width = 0, height = 0;
  bool scene_rect = true;
  auto operator<=>(const RunKey&) const = default;
};

// Appends each run's rows to a results CSV as one unit (CsvAppender: one
// write under an flock, the header written once, a foreign header refused,
// a torn end cut back to the last complete run). Every row carries the
// run's run_id and run_rows, so a reader can tell a whole run from a part.
// Rows of the wrong width and incomplete runs inside the file are reported
// on stderr with their line numbers (problems()); they never count as done.
class CsvWriter {
 public:
  explicit CsvWriter(const std::string& path);
  // Returns the run_id written.
  std::string write(const RunResult& result, const RunContext& context);
  // The runs the file holds whole with an `ok` or `skipped` status, read
  // under the lock (for --resume; see finished_runs).
  std::set<RunKey> finished_runs() const;
  const std::string& path() const { return csv_.path(); }
  const std::vector<std::string>& problems() const { return problems_; }
  const std::string& repair_note() const { return csv_.repair_note(); }

 private:
  CsvAppender csv_;
  std::vector<std::string> problems_;
};

// A new run id, unique across processes and hosts: a random prefix per
// process and a counter.
std::string new_run_id();
std::vector<std::vector<std::string>> csv_rows(const RunResult& result, const RunContext& context,
                                               const std::string& run_id = "");
std::string utc_timestamp();

// The runs a results CSV holds whole (all run_rows rows of their run_id
// present, each of the header's width) with status `ok` or `skipped` (an
// `error` run is not finished: it is run again). None when the file is
// missing or empty; throws like CsvWriter when its header is not ours. A
// torn last line or an incomplete run never counts; `problems`, when
// given, receives "line N: ..." for each row that is not part of a whole run.
std::set<RunKey> finished_runs(const std::string& path);

// The runs a results CSV's contents hold whole, in the order of their first
// rows: each the rows of one run_id, all run_rows of them, each of the
// header's width. Throws like CsvWriter when the header is not ours; `problems`,
// when given, receives "line N: ..." for each row that is not part of a whole run.
using CsvRun = std::vector<const CsvRecord*>;
std::vector<CsvRun> whole_runs(const CsvContents& contents, const std::string& path,
                               std::vector<std::string>* problems = nullptr);
// The "name=value name=value" text of the params, scene_params, extra and
// work_saved columns as pairs, in order (no value holds a space or '=':
// base/params.h refuses them, figures are numbers).
std::vector<std::pair<std::string, std::string>> csv_pairs(const std::string& text);

// The index of a column of csv_columns() by name; throws naming an unknown one.
size_t csv_column(const std::string& name);
std::set<RunKey> finished_runs(const CsvContents& contents, const std::string& path,
                               std::vector<std::string>* problems = nullptr);

// `bench --resume` in several processes on one CSV: before running a
// configuration, a process claims it with a lock on one byte of FILE.claims
// (an OFD lock at an offset hashed from the RunKey; the file stays empty).
// A run another process has claimed is left to it; the lock goes when the
// claim is dropped or its process ends, even when killed. After claiming,
// the process reads the CSV again, so a run finished meanwhile is not run twice.
class RunClaims {
 public:
  explicit RunClaims(const std::string& csv_path);
  ~RunClaims();
  RunClaims(const RunClaims&) = delete;
  RunClaims& operator=(const RunClaims&) = delete;

  class Claim {
   public:
    Claim(int fd, int64_t offset) : fd_(fd), offset_(offset) {}
    Claim(Claim&& other) noexcept : fd_(std::exchange(other.fd_, -1)), offset_(other.offset_) {}
    Claim& operator=(Claim&&) = delete;
    ~Claim();

   private:
    int fd_;
    int64_t offset_;
  };
  // nullopt: another process holds this run.
  std::optional<Claim> try_claim(const RunKey& key);

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace oit
