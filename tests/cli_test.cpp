// The command line as users call it: `oitbench render` of the reference
// equals the closed form, `oitbench bench --clock both` writes a row per
// stage and clock of every technique, bad input exits non-zero with the key.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

#include "harness/app/commands.h"
#include "harness/core/image.h"
#include "tests/oitbench_process.h"
#include "harness/core/results_csv.h"
#include "harness/core/technique.h"
#include "scenes/scene_library.h"
#include "scenes/stacked_quads.h"

namespace oit {
namespace {

using test::Outcome;

const std::string kOut = std::string(OIT_BINARY_DIR) + "/test_output/cli";

Outcome run_oitbench(const std::string& arguments) { return test::run_oitbench(kOut, arguments); }


// The README's technique table sits between these markers, written by
// `oitbench list --markdown`: a new technique folder changes it there and
// only there (regenerate it with that command).
TEST(Cli, ReadmeTechniqueTableIsTheGeneratedOne) {
  std::ifstream readme(std::string(OIT_SOURCE_DIR) + "/README.md");
  ASSERT_TRUE(readme) << "README.md";
  const std::string text((std::istreambuf_iterator<char>(readme)), std::istreambuf_iterator<char>());
  const std::string begin = "<!-- technique table: oitbench list --markdown -->\n", end = "<!-- end of technique table -->";
  const size_t from = text.find(begin), to = text.find(end);
  ASSERT_NE(from, std::string::npos) << "README.md lacks the marker " << begin;
  ASSERT_NE(to, std::string::npos) << "README.md lacks the marker " << end;
  const std::string generated = technique_table_markdown(builtin_techniques());
  EXPECT_EQ(text.substr(from + begin.size(), to - from - begin.size()), generated)
      << "README.md's technique table is stale: replace it with the output of `oitbench list --markdown`";
  // The command prints exactly that table, without opening a GL context.
  const Outcome o = run_oitbench("list --markdown");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find(generated), std::string::npos) << o.output;
}

TEST(Cli, RenderOfTheReferenceEqualsTheClosedFormExactly) {
  const std::string out = kOut + "/reference_quads.pfm";
  std::filesystem::remove(out);
  const Outcome o = run_oitbench("render --technique reference --scene quads --size 64x64 --out " + out);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const Image image = read_pfm(out);
  ASSERT_EQ(image.width, 64);
  ASSERT_EQ(image.height, 64);
  const glm::vec4 expected = stacked_quads_closed_form(StackedQuadsParams{}, glm::vec3(0.0f));
  size_t mismatches = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) mismatches += image.at(x, y, c) != expected[c];
  EXPECT_EQ(mismatches, 0u);
}

TEST(Cli, BenchWithBothClocksWritesEveryStageOfEveryTechniqueTwice) {
  const std::string csv = kOut + "/both_clocks.csv";
  std::filesystem::remove(csv);
  const Outcome o = run_oitbench(
      "bench --technique unsorted --technique reference --scene quads --scene-set layers=4 --size 32x32 "
      "--warmup 1 --frames 2 --clock both --csv " + csv);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("technique"), std::string::npos) << "no summary table:\n" << o.output;

  const test::CsvTable table = test::read_csv_table(csv);
  ASSERT_EQ(table.header, csv_columns());
  auto column = [&](const std::string& name) { return table.column(name); };
  std::set<std::string> seen;  // technique/stage/clock
  for (const auto& row : table.rows) {
    ASSERT_EQ(row.size(), table.header.size());
    EXPECT_EQ(row[column("status")], "ok") << row[column("message")];
    EXPECT_FALSE(row[column("median_ms")].empty()) << row[column("technique")] << " " << row[column("stage")];
    EXPECT_FALSE(row[column("device")].empty());
    seen.insert(row[column("technique")] + "/" + row[column("stage")] + "/" + row[column("clock")]);
  }
  for (const char* id : {"unsorted", "reference"}) {
    std::vector<std::string> stages = builtin_techniques().get(id).stages;
    stages.push_back("total");
    for (const auto& stage : stages)
      for (const char* clock : {"gl", "wall"})
        EXPECT_TRUE(seen.count(std::string(id) + "/" + stage + "/" + clock)) << id << " " << stage << " " << clock;
  }
}

TEST(Cli, StatsPrintsTheQuadsComplexityAndWritesTheHeatmap) {
  // 8 full-screen layers: every pixel's list has 8 fragments, so Psi = 1.
  const std::string heatmap = kOut + "/stats_heatmap.png";
  std::filesystem::remove(heatmap);
  const Outcome o = run_oitbench("stats --scene quads --scene-set layers=8 --size 16x8 --heatmap " + heatmap);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("fragments         1,024"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("depth complexity  max 8, mean 8.000"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("psi               1.0000"), std::string::npos) << o.output;
  EXPECT_GT(std::filesystem::file_size(heatmap), 0u);
}

TEST(Cli, BenchSummaryNamesTheSweptSceneParameters) {
  const std::string csv = kOut + "/swept_scene.csv";
  std::filesystem::remove(csv);
  const Outcome o = run_oitbench("bench --technique unsorted --scene quads --scene-set layers=2,3 --size 8x8 "
                                 "--frames 1 --warmup 0 --csv " + csv);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("quads layers=2 "), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("quads layers=3 "), std::string::npos) << o.output;
}

TEST(Cli, BadParameterExitsNonZeroNamingTheKey) {
  const Outcome o = run_oitbench("render --technique reference --set initial_nodes_per_pixel=0 --scene quads "
                                 "--size 8x8 --out " + kOut + "/never.png");
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find("initial_nodes_per_pixel"), std::string::npos) << o.output;
  EXPECT_FALSE(std::filesystem::exists(kOut + "/never.png"));

  const Outcome size = run_oitbench("render --technique unsorted --scene quads --size 8by8 --out " + kOut + "/x.png");
  EXPECT_NE(size.exit_code, 0);
  EXPECT_NE(size.output.find("8by8"), std::string::npos) << size.output;
}

// --device egl:N takes the N-th EGL device as `list` numbers them: on the
// software-GL machines of CI that is Mesa's software device (llvmpipe); an
// index past the last device and a malformed one are errors naming the value.
TEST(Cli, DeviceEglIndexPicksThatDeviceAndNamesTheDevicesWhenOutOfRange) {
  const Outcome listed = run_oitbench("list");
  ASSERT_EQ(listed.exit_code, 0) << listed.output;
  const size_t software = listed.output.find("    egl:");
  ASSERT_NE(software, std::string::npos) << "no EGL device listed:\n" << listed.output;
  const std::string index = listed.output.substr(software + 8, listed.output.find(' ', software + 8) - software - 8);
  const Outcome picked = run_oitbench("--device egl:" + index + " list");
  ASSERT_EQ(picked.exit_code, 0) << picked.output;
  EXPECT_NE(picked.output.find("Device: llvmpipe"), std::string::npos) << picked.output;
  EXPECT_NE(picked.output.find(", egl-device, host pages"), std::string::npos) << picked.output;

  const Outcome past = run_oitbench("--device egl:99 list");
  EXPECT_NE(past.exit_code, 0);
  EXPECT_NE(past.output.find("--device egl:99: this machine has"), std::string::npos) << past.output;
  EXPECT_NE(past.output.find("egl:" + index + " software"), std::string::npos) << past.output;

  const Outcome malformed = run_oitbench("--device egl:first list");
  EXPECT_NE(malformed.exit_code, 0);
  EXPECT_NE(malformed.output.find("device 'egl:first' is not one of auto, gpu, software, egl:N"), std::string::npos)
      << malformed.output;
}

TEST(Cli, BenchKeepsGoingPastAFailingRunAndRecordsIt) {
  const std::string csv = kOut + "/error_row.csv";
  std::filesystem::remove(csv);
  // The second scene file does not exist: an error row, and the first run still lands.
  const Outcome o = run_oitbench("bench --technique unsorted --scene quads --scene missing_scene.gltf --size 8x8 "
                                 "--warmup 0 --frames 1 --csv " + csv);
  EXPECT_EQ(o.exit_code, kExitRunsFailed) << o.output;  // every row written, the failure still reported
  EXPECT_NE(o.output.find("1 run failed"), std::string::npos) << o.output;
  std::ifstream in(csv);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find(",ok,"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("missing_scene.gltf' does not exist"), std::string::npos) << text.str();
}

// A budget too small for any reference tile plan: the run keeps its timings,
// its error columns stay empty, and the console says why instead of crashing.
TEST(Cli, BenchRunWithoutAReferenceKeepsItsTimingsAndSaysWhy) {
  const std::string csv = kOut + "/no_reference.csv";
  std::filesystem::remove(csv);
  const Outcome o = run_oitbench("bench --technique unsorted --scene quads --size 16x16 --warmup 0 --frames 1 "
                                 "--background 0.5,0.25,0.125 --memory-budget 64 --csv " + csv);
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("no reference image"), std::string::npos) << o.output;
  const test::CsvTable table = test::read_csv_table(csv);
  ASSERT_FALSE(table.rows.empty());
  for (const auto& row : table.rows) {
    EXPECT_EQ(row[table.column("status")], "ok");
    EXPECT_EQ(row[table.column("error_max")], "");
    EXPECT_NE(row[table.column("message")].find("no reference image"), std::string::npos);
    if (row[table.column("stage")] == "total") EXPECT_NE(row[table.column("median_ms")], "");
  }
}

TEST(Cli, StressCaseFilterMatchingNothingIsAnError) {
  const Outcome o = run_oitbench("stress --technique unsorted --case no_such_case");
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("no case matches --case 'no_such_case'"), std::string::npos) << o.output;
}

std::vector<std::vector<std::string>> rows_of(const std::string& csv, const std::string& technique) {
  std::vector<std::vector<std::string>> rows;
  const auto records = read_csv(csv);
  const size_t column = size_t(std::find(csv_columns().begin(), csv_columns().end(), "technique") -
                               csv_columns().begin());
  for (size_t i = 1; i < records.size(); ++i)
    if (records[i][column] == technique) rows.push_back(records[i]);
  return rows;
}

TEST(Cli, BenchResumeRunsNothingTwiceAndMatchesCanonicalParameters) {
  const std::string csv = kOut + "/resume.csv";
  std::filesystem::remove(csv);
  const std::string sweep = "bench --technique unsorted --technique kbuffer --scene quads --scene-set layers=4 "
                            "--size 16x16 --warmup 0 --frames 1 --resume --csv " + csv;
  const Outcome first = run_oitbench(sweep);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find("runs: 2 done (2 ok, 0 error), 0 resumed"), std::string::npos) << first.output;
  const size_t rows = read_csv(csv).size();
  ASSERT_GT(rows, 3u);
  // k=16 is kbuffer's default and seed=1 the scene's: the rows written without them are the same runs.
  const Outcome second = run_oitbench(sweep + " --set kbuffer.k=16 --scene-set seed=1");
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(second.output.find("[1/2] unsorted on quads 16x16 ... already in " + csv + ", not run again"),
            std::string::npos) << second.output;
  EXPECT_NE(second.output.find("[2/2] kbuffer k=16 on quads 16x16 ... already in " + csv + ", not run again"),
            std::string::npos) << second.output;
  EXPECT_NE(second.output.find("runs: 0 done (0 ok, 0 error), 2 resumed"), std::string::npos) << second.output;
  EXPECT_EQ(read_csv(csv).size(), rows);
  // Without --resume the same sweep runs again.
  const Outcome again = run_oitbench("bench --technique unsorted --scene quads --scene-set layers=4 --size 16x16 "
                                     "--warmup 0 --frames 1 --csv " + csv);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_GT(read_csv(csv).size(), rows);
}

TEST(Cli, BenchResumeRunsErrorRowsAgainAndKeepsSkippedOnes) {
  const std::string csv = kOut + "/resume_error.csv";
  std::filesystem::remove(csv);
  {
    // Written as an earlier invocation would have: unsorted failed, kbuffer was skipped
    // (quoted messages with commas, quotes and a newline).
    CsvWriter writer(csv);
    const RunContext context{"llvmpipe", "4.5", "egl-surfaceless", "abc1234", "2026-11-22T09:00:00Z"};
    RunResult failed;
    failed.spec.technique = "unsorted";
    failed.spec.scene = "quads";
    failed.spec.width = failed.spec.height = 16;
    failed.scene_params = canonical_scene_params("quads", {{"layers", "4"}});
    failed.status = RunStatus::error;
    failed.message = "out of memory, \"really\"\nsecond line";
    writer.write(failed, context);
    RunResult skipped = failed;
    skipped.spec.technique = "kbuffer";
    skipped.technique_params = "k=16 tail=drop auto_k_memory_mb=1024";  // every parameter, defaults included
    skipped.status = RunStatus::skipped;
    skipped.message = "needs something, \"else\"";
    writer.write(skipped, context);
  }
  const Outcome o = run_oitbench("bench --technique unsorted --technique kbuffer --scene quads --scene-set layers=4 "
                                 "--size 16x16 --warmup 0 --frames 1 --resume --csv " + csv);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("[2/2] kbuffer on quads 16x16 ... already in"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("runs: 1 done (1 ok, 0 error), 1 resumed"), std::string::npos) << o.output;
  EXPECT_EQ(rows_of(csv, "kbuffer").size(), 1u);  // only the old skipped row
  const auto unsorted = rows_of(csv, "unsorted");
  ASSERT_GT(unsorted.size(), 1u);
  const size_t status = size_t(std::find(csv_columns().begin(), csv_columns().end(), "status") - csv_columns().begin());
  EXPECT_EQ(unsorted.front()[status], "error");
  EXPECT_EQ(unsorted.back()[status], "ok");
}

TEST(Cli, GoogleBenchmarkBinaryReportsManualTimeAndCounters) {
  const std::string json_path = kOut + "/gbench.json";
  std::filesystem::create_directories(kOut);
  const std::string command = std::string(OIT_BINARY_DIR) + "/harness/oitbench_gbench --benchmark_filter=reference " +
                              "--benchmark_format=json --technique unsorted --technique reference " +
                              "--scene-set layers=4 --size 16x16 > " + json_path + " 2>/dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream in(json_path);
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_FALSE(report["context"]["device"].get<std::string>().empty());
  ASSERT_EQ(report["benchmarks"].size(), 1u) << report.dump(2);  // the filter left only the reference
  const auto& run = report["benchmarks"][0];
  EXPECT_EQ(run["name"].get<std::string>().rfind("reference/", 0), 0u);
  EXPECT_GT(run["real_time"].get<double>(), 0.0);
  EXPECT_EQ(run["error_max"].get<double>(), 0.0);
  EXPECT_EQ(run["fragments"].get<double>(), 4.0 * 16 * 16);
}

}  // namespace
}  // namespace oit
