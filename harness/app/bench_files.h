#pragma once
// The optional files of `oitbench bench` besides its results CSV, both
// written through the checked writers of harness/output (output_file.h,
// csv_file.h), so a full disk or a bad path is an error naming the file:
//  - --samples FILE: every timed frame's time of every stage, one row each
//    (the CSV keeps only summaries), appended one run at a time;
//  - --json FILE: this invocation's runs as one JSON document, rewritten
//    whole (temporary file, rename) after each run, so it always parses.
#include <memory>
#include <string>
#include <vector>

#include "harness/output/csv_file.h"
#include "harness/run/results_csv.h"

namespace oit {

// run_id, technique, params, scene, scene_params, camera, width, height,
// scene_rect, clock, stage, frame (from 0, in timed order), ms.
const std::vector<std::string>& sample_columns();

class SamplesCsv {
 public:
  explicit SamplesCsv(const std::string& path);
  // The run's per-frame samples as one unit; nothing for a run without timings.
  void append(const RunResult& result, const std::string& run_id);

 private:
  CsvAppender csv_;
};

// {"device", "gl_version", "platform", "git_revision", "timestamp", "runs": [...]}:
// each run holds the CSV's figures under the CSV's column names, with
// `params`, `scene_params`, `extra` and `work_saved` as objects (parameter
// values as their canonical text: "16", "drop"), `error` as an object and
// `stages` as a list whose entries carry their samples_ms; null where the
// CSV's cell is empty.
class BenchJson {
 public:
  BenchJson(std::string path, const RunContext& context);
  ~BenchJson();
  // Adds the run and rewrites the file.
  void add(const RunResult& result, const std::string& run_id);

 private:
  struct Document;
  std::string path_;
  std::unique_ptr<Document> document_;
};

}  // namespace oit
