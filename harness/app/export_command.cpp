// `oitbench export --wide RESULTS.csv -o WIDE.csv`: the long-form results
// CSV (one row per run x stage x clock, parameters as "k=16 tail=drop" text)
// as one row per run with every figure in a column of its own, for
// spreadsheets and for analysis that should not parse text.
#include <algorithm>
#include <cstdio>
#include <map>

#include "harness/app/commands.h"
#include "harness/output/csv_file.h"
#include "harness/output/output_file.h"
#include "harness/run/results_csv.h"

namespace oit {
namespace {

// The per-run columns kept as they are (the stage, clock and time columns
// become per-stage columns; run_rows means nothing in a row per run).
std::vector<std::string> kept_columns() {
  std::vector<std::string> kept;
  for (const auto& name : csv_columns())
    if (name != "clock" && name != "stage" && name != "median_ms" && name != "min_ms" && name != "p05_ms" &&
        name != "p95_ms" && name != "mean_ms" && name != "work_saved" && name != "extra" && name != "run_rows")
      kept.push_back(name);
  return kept;
}

const std::vector<std::string> kTimes = {"median_ms", "min_ms", "p05_ms", "p95_ms", "mean_ms"};

// Column names in the order they first appear, and each run's values by name.
struct WideTable {
  std::vector<std::string> columns;
  std::vector<std::map<std::string, std::string>> rows;
  void set(std::map<std::string, std::string>& row, const std::string& column, const std::string& value) {
    if (std::find(columns.begin(), columns.end(), column) == columns.end()) columns.push_back(column);
    row[column] = value;
  }
};

// The prefixed pairs of each run first (param., scene., extra., work_saved.),
// then the times, so that a table's columns group by kind.
WideTable widen(const std::vector<CsvRun>& runs) {
  WideTable table;
  table.columns = kept_columns();
  table.rows.resize(runs.size());
  const std::vector<std::pair<std::string, std::string>> prefixed = {
      {"params", "param."}, {"scene_params", "scene."}, {"extra", "extra."}, {"work_saved", "work_saved."}};
  for (const auto& [source, prefix] : prefixed)
    for (size_t i = 0; i < runs.size(); ++i)
      for (const auto& [name, value] : csv_pairs(runs[i].front()->fields[csv_column(source)]))
        table.set(table.rows[i], prefix + name, value);
  for (size_t i = 0; i < runs.size(); ++i) {
    for (const auto& name : kept_columns()) table.rows[i][name] = runs[i].front()->fields[csv_column(name)];
    for (const CsvRecord* row : runs[i]) {
      const std::string& stage = row->fields[csv_column("stage")];
      if (stage.empty()) continue;  // a skipped or error run's one row: no times
      for (const auto& time : kTimes)
        table.set(table.rows[i], stage + "." + row->fields[csv_column("clock")] + "." + time,
                  row->fields[csv_column(time)]);
    }
  }
  return table;
}

}  // namespace

int run_export(const ExportOptions& options) {
  std::vector<std::string> problems;
  const CsvContents contents = read_csv_file(options.wide, "results CSV");
  if (contents.records.empty() && !contents.torn)
    throw std::invalid_argument("results CSV '" + options.wide + "' does not exist or is empty");
  const std::vector<CsvRun> runs = whole_runs(contents, options.wide, &problems);
  for (const auto& problem : problems)
    std::fprintf(stderr, "oitbench export: '%s', %s: left out\n", options.wide.c_str(), problem.c_str());
  const WideTable table = widen(runs);
  std::string text = csv_line(table.columns);
  for (const auto& row : table.rows) {
    std::vector<std::string> fields;
    for (const auto& column : table.columns) {
      const auto at = row.find(column);
      fields.push_back(at == row.end() ? "" : at->second);
    }
    text += csv_line(fields);
  }
  write_file_atomically(options.out, text);
  std::printf("%zu runs, %zu columns -> %s\n", table.rows.size(), table.columns.size(), options.out.c_str());
  return 0;
}

}  // namespace oit
