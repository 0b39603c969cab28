// The long-form CSV contract: header, one row per stage x clock, per-run
// columns repeated, skipped/error rows, escaping, appending.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "harness/run/results_csv.h"

namespace oit {
namespace {

RunContext context() { return {"llvmpipe (LLVM 15.0.6, 256 bits)", "4.5 (Core Profile) Mesa 22.3.6", "egl-surfaceless", "abc1234", "2026-11-22T09:00:00Z"}; }

RunResult finished_run() {
  RunResult r;
  r.spec.technique = "kbuffer";
  r.spec.scene = "quads";
  r.spec.width = 64;
  r.spec.height = 32;
  r.spec.warmup = 2;
  r.technique_params = "k=16 tail=drop";
  r.scene_params = "layers=32";
  r.clock = ClockKind::both;
  for (const char* clock : {"gl", "wall"}) {
    for (const char* stage : {"fill", "compose", "total"}) {
      StageResult s{stage, clock, summarize({1.0, 2.0, 3.0}), {1.0, 2.0, 3.0}};
      r.stages.push_back(s);
    }
  }
  r.counters.bytes_allocated = 4096;
  r.counters.fragments_dropped = 7;
  r.counters.passes = 2;
  r.counters.extra = {{"links_left", 12.0}, {"neighbor_precision", 0.5}};
  r.counters.work_saved = {{"passes_avoided", 30.0}};
  r.error = ImageError{0.5, 0.25, 12.0};
  r.scene_fragments = 65536;
  r.max_depth_complexity = 32;
  r.psi = 0.25;
  r.spec.camera = "random:4:7@2";
  return r;
}

size_t column(const std::string& name) {
  const auto& columns = csv_columns();
  return size_t(std::find(columns.begin(), columns.end(), name) - columns.begin());
}

// Each named column of `row` holds the value paired with it.
void expect_columns(const std::vector<std::string>& row,
                    const std::vector<std::pair<std::string, std::string>>& expected) {
  for (const auto& [name, value] : expected) EXPECT_EQ(row[column(name)], value) << name;
}

TEST(ResultsCsv, OneRowPerStageAndClockWithPerRunColumnsRepeated) {
  const auto rows = csv_rows(finished_run(), context());
  ASSERT_EQ(rows.size(), 6u);
  for (const auto& row : rows) {
    ASSERT_EQ(row.size(), csv_columns().size());
    expect_columns(row, {{"technique", "kbuffer"},
                         {"params", "k=16 tail=drop"},
                         {"status", "ok"},
                         {"fragments_dropped", "7"},
                         {"error_max", "0.5"},
                         {"median_ms", "2"},
                         {"frames", "3"},
                         {"device", "llvmpipe (LLVM 15.0.6, 256 bits)"},
                         {"extra", "links_left=12 neighbor_precision=0.5"},
                         {"work_saved", "passes_avoided=30"},
                         {"camera", "random:4:7@2"},
                         {"psi", "0.25"},
                         {"scene_rect", "on"}});
  }
  expect_columns(rows[0], {{"clock", "gl"}});
  expect_columns(rows[5], {{"clock", "wall"}, {"stage", "total"}});
  RunResult full_screen = finished_run();
  full_screen.spec.scene_rect = false;
  EXPECT_EQ(csv_rows(full_screen, context())[0][column("scene_rect")], "off");
}

TEST(ResultsCsv, SkippedAndFailedRunsAreOneRowWithTheReason) {
  RunResult skipped;
  skipped.spec.technique = "reference";
  skipped.status = RunStatus::skipped;
  skipped.message = "needs 64-bit integers in shaders, which the device lacks";
  auto rows = csv_rows(skipped, context());
  ASSERT_EQ(rows.size(), 1u);
  expect_columns(rows[0], {{"status", "skipped"},
                           {"message", skipped.message},
                           {"median_ms", ""},
                           {"error_max", ""},
                           {"camera", "default"},
                           {"psi", ""}});

  RunResult failed = skipped;
  failed.status = RunStatus::error;
  failed.message = "technique 'kbuffer' parameter 'k' = 0 is out of range [1, 64]";
  rows = csv_rows(failed, context());
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0][column("status")], "error");
}

TEST(ResultsCsv, FieldsWithCommasQuotesOrNewlinesAreQuoted) {
  EXPECT_EQ(csv_escape("plain"), "plain");
  EXPECT_EQ(csv_escape("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_escape("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_escape("two\nlines"), "\"two\nlines\"");
}

TEST(ResultsCsv, WriterAppendsUnderOneHeaderAndRefusesAForeignFile) {
  const std::string path = std::string(OIT_BINARY_DIR) + "/test_output/results_csv_test.csv";
  std::filesystem::remove(path);
  {
    CsvWriter writer(path);
    writer.write(finished_run(), context());
  }
  {
    CsvWriter writer(path);  // appends, no second header
    writer.write(finished_run(), context());
  }
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(in, line)) lines.push_back(line);
  ASSERT_EQ(lines.size(), 13u);
  EXPECT_EQ(lines[0].rfind("timestamp,git_revision,device,", 0), 0u);
  // The renderer string holds a comma, so it is quoted.
  EXPECT_NE(lines[1].find("\"llvmpipe (LLVM 15.0.6, 256 bits)\""), std::string::npos) << lines[1];

  const std::string foreign = std::string(OIT_BINARY_DIR) + "/test_output/foreign.csv";
  std::ofstream(foreign) << "a,b,c\n1,2,3\n";
  try {
    CsvWriter writer(foreign);
    FAIL() << "a CSV with other columns was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("foreign.csv"), std::string::npos) << e.what();
  }
}

TEST(ResultsCsv, ReaderReturnsWhatTheWriterWroteAndFinishedRunsLeaveErrorsOut) {
  const std::string path = std::string(OIT_BINARY_DIR) + "/test_output/results_csv_resume.csv";
  std::filesystem::remove(path);
  EXPECT_TRUE(finished_runs(path).empty());  // no file yet: nothing finished
  RunResult ok = finished_run();
  ok.counters.extra = {{"a", 1.0}};
  RunResult failed = finished_run();
  failed.spec.technique = "linked_list";
  failed.status = RunStatus::error;
  failed.message = "pool, \"full\"\nsecond line";  // comma, quotes and a newline: all quoted
  RunResult skipped = finished_run();
  skipped.spec.camera = "default";
  skipped.status = RunStatus::skipped;
  skipped.message = " leading and trailing spaces ";
  RunResult without_rect = skipped;  // the same run with the scene rectangle off is another run
  without_rect.spec.scene_rect = false;
  std::vector<std::string> run_ids;
  {
    CsvWriter writer(path);
    for (const RunResult* r : {&ok, &failed, &skipped, &without_rect}) run_ids.push_back(writer.write(*r, context()));
  }
  const auto records = read_csv(path);
  ASSERT_EQ(records.size(), 1u + 6u + 1u + 1u + 1u);
  EXPECT_EQ(records[0], csv_columns());
  EXPECT_EQ(records[1], csv_rows(ok, context(), run_ids[0])[0]);
  EXPECT_EQ(records[7], csv_rows(failed, context(), run_ids[1])[0]);
  EXPECT_NE(run_ids[0], run_ids[1]);
  EXPECT_EQ(records[6][column("run_rows")], "6");
  EXPECT_EQ(records[8][column("run_rows")], "1");
  EXPECT_EQ(records[7][column("message")], "pool, \"full\"\nsecond line");
  EXPECT_EQ(records[8][column("message")], " leading and trailing spaces ");

  const std::set<RunKey> finished = finished_runs(path);
  const std::set<RunKey> expected = {
      {"kbuffer", "k=16 tail=drop", "quads", "layers=32", "random:4:7@2", 64, 32},
      {"kbuffer", "k=16 tail=drop", "quads", "layers=32", "default", 64, 32},
      {"kbuffer", "k=16 tail=drop", "quads", "layers=32", "default", 64, 32, false}};
  EXPECT_EQ(finished, expected);  // the linked_list error row is not finished

  // A row cut short by a crash while writing is no run; the rows before it still count.
  std::ofstream(path, std::ios::app) << "2026-11-22T09:00:00Z,abc1234,\"llvmpipe";
  EXPECT_EQ(finished_runs(path), expected);

  const std::string foreign = std::string(OIT_BINARY_DIR) + "/test_output/foreign_resume.csv";
  std::ofstream(foreign) << "a,b,c\n1,2,3\n";
  try {
    finished_runs(foreign);
    FAIL() << "a CSV with other columns was read as ours";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("foreign_resume.csv' exists with different columns"), std::string::npos)
        << e.what();
  }
}

TEST(ResultsCsv, LargeExtraCountsAreWrittenExactly) {
  RunResult r = finished_run();
  r.counters.extra = {{"scene_triangles", 1234567.0}, {"scene_vertices", 98765432.0}};
  EXPECT_EQ(csv_rows(r, context())[0][column("extra")], "scene_triangles=1234567 scene_vertices=98765432");
}

}  // namespace
}  // namespace oit
