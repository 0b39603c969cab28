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

#include "harness/app/bench_files.h"

#include "harness/app/commands.h"
#include "harness/app/pareto.h"
#include "harness/output/image.h"
#include "tests/oitbench_process.h"
#include "harness/run/results_csv.h"
#include "harness/toolkit/technique.h"
#include "scenes/scene_library.h"
#include "scenes/stacked_quads.h"

namespace oit {
namespace {

using test::Outcome;

const std::string kOut = std::string(OIT_BINARY_DIR) + "/test_output/cli";

Outcome run_oitbench(const std::string& arguments) { return test::run_oitbench(kOut, arguments); }

// <kOut>/<name>, removed: the output file of a test that must not find an
// earlier run's.
std::string fresh_output(const std::string& name) {
  const std::string path = kOut + "/" + name;
  std::filesystem::remove(path);
  return path;
}

// The output with the console's wrapped lines (continued after "\n    ") joined again.
std::string unwrapped(std::string text) {
  for (size_t at = text.find("\n    "); at != std::string::npos; at = text.find("\n    ", at)) text.replace(at, 5, " ");
  return text;
}


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
  const std::string out = fresh_output("reference_quads.pfm");
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
  const std::string csv = fresh_output("both_clocks.csv");
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
  const std::string heatmap = fresh_output("stats_heatmap.png");
  const Outcome o = run_oitbench("stats --scene quads --scene-set layers=8 --size 16x8 --heatmap " + heatmap);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("fragments         1,024"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("depth complexity  max 8, mean 8.000"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("psi               1.0000"), std::string::npos) << o.output;
  EXPECT_GT(std::filesystem::file_size(heatmap), 0u);
}

TEST(Cli, BenchSummaryNamesTheSweptSceneParameters) {
  const std::string csv = fresh_output("swept_scene.csv");
  const Outcome o = run_oitbench("bench --technique unsorted --scene quads --scene-set layers=2,3 --size 8x8 "
                                 "--frames 1 --warmup 0 --csv " + csv);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("-- quads layers=2, 8x8\n"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("-- quads layers=3, 8x8\n"), std::string::npos) << o.output;
  // The progress lines tell the two apart too.
  EXPECT_NE(o.output.find("[1/2] unsorted on quads layers=2 8x8 ... "), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("[2/2] unsorted on quads layers=3 8x8 ... "), std::string::npos) << o.output;
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
  const std::string csv = fresh_output("error_row.csv");
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
  const std::string csv = fresh_output("no_reference.csv");
  const Outcome o = run_oitbench("bench --technique unsorted --scene quads --size 16x16 --warmup 0 --frames 1 "
                                 "--background 0.5,0.25,0.125 --memory-budget 64 --csv " + csv);
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(unwrapped(o.output).find("no reference image"), std::string::npos) << o.output;
  const test::CsvTable table = test::read_csv_table(csv);
  ASSERT_FALSE(table.rows.empty());
  for (const auto& row : table.rows) {
    EXPECT_EQ(row[table.column("status")], "ok");
    EXPECT_EQ(row[table.column("error_max")], "");
    EXPECT_NE(row[table.column("message")].find("no reference image"), std::string::npos);
    if (row[table.column("stage")] == "total") {
      EXPECT_NE(row[table.column("median_ms")], "");
    }
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
  const std::string csv = fresh_output("resume.csv");
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
  EXPECT_NE(unwrapped(second.output).find("[1/2] unsorted on quads layers=4 seed=1 16x16 ... already in " + csv +
                                          ", not run again [elapsed "),
            std::string::npos) << second.output;
  EXPECT_NE(unwrapped(second.output).find("[2/2] kbuffer k=16 on quads layers=4 seed=1 16x16 ... already in " + csv +
                                          ", not run again [elapsed "),
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
  const std::string csv = fresh_output("resume_error.csv");
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
    skipped.technique_params = "k=16 tail=drop slot_layout=full auto_k_memory_mb=1024";  // every parameter, defaults included
    skipped.status = RunStatus::skipped;
    skipped.message = "needs something, \"else\"";
    writer.write(skipped, context);
  }
  const Outcome o = run_oitbench("bench --technique unsorted --technique kbuffer --scene quads --scene-set layers=4 "
                                 "--size 16x16 --warmup 0 --frames 1 --resume --csv " + csv);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(unwrapped(o.output).find("[2/2] kbuffer on quads layers=4 16x16 ... already in"), std::string::npos)
      << o.output;
  EXPECT_NE(o.output.find("runs: 1 done (1 ok, 0 error), 1 resumed"), std::string::npos) << o.output;
  EXPECT_EQ(rows_of(csv, "kbuffer").size(), 1u);  // only the old skipped row
  const auto unsorted = rows_of(csv, "unsorted");
  ASSERT_GT(unsorted.size(), 1u);
  const size_t status = size_t(std::find(csv_columns().begin(), csv_columns().end(), "status") - csv_columns().begin());
  EXPECT_EQ(unsorted.front()[status], "error");
  EXPECT_EQ(unsorted.back()[status], "ok");
}

// ---- issue 21: output people can read and trust ----

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// A CSV cell ("1.23456") as the summary prints it ("1.23").
std::string two_decimals(const std::string& cell) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", std::stod(cell));
  return text;
}

// The summary's row of `technique` (the first line that starts with it and a space).
std::string summary_row(const std::string& output, const std::string& technique) {
  for (const auto& line : lines_of(output))
    if (line.rfind(technique + " ", 0) == 0) return line;
  return "";
}

TEST(Cli, BenchConsoleFitsIn120ColumnsWithSpreadRatioAndNonDefaultParameters) {
  const std::string csv = fresh_output("summary.csv");
  const Outcome o = run_oitbench("bench --technique kbuffer --technique unsorted --set kbuffer.k=4 "
                                 "--set kbuffer.tail=drop --scene quads --scene-set layers=4 --size 16x16 "
                                 "--warmup 0 --frames 3 --csv " + csv);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  for (const auto& line : lines_of(o.output)) EXPECT_LE(line.size(), 120u) << "'" << line << "'";
  EXPECT_NE(o.output.find("technique                  params               status  median±95% ms     "
                          "x unsorted [95%] max error   dropped noisy\n-- quads layers=4, 16x16\n"),
            std::string::npos) << o.output;
  // Progress: the runs told apart, the elapsed time, and what is left while runs remain.
  EXPECT_NE(o.output.find("[1/2] kbuffer k=4 tail=drop on quads layers=4 16x16 ... "), std::string::npos) << o.output;
  EXPECT_NE(unwrapped(o.output).find(" [elapsed 0:"), std::string::npos) << o.output;
  EXPECT_NE(unwrapped(o.output).find(", ETA 0:"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("(x unsorted: median total over unsorted's in the same block"), std::string::npos)
      << o.output;
  // Rows: kbuffer names k (swept) and tail (given) but not auto_k_memory_mb (a default left alone).
  const std::string unsorted = summary_row(o.output, "unsorted"), kbuffer = summary_row(o.output, "kbuffer");
  ASSERT_FALSE(unsorted.empty()) << o.output;
  ASSERT_FALSE(kbuffer.empty()) << o.output;
  EXPECT_EQ(kbuffer.substr(27, 21), "k=4 tail=drop        ") << kbuffer;
  EXPECT_EQ(unsorted.substr(27, 29), "                     ok      ") << unsorted;
  EXPECT_EQ(unsorted.substr(71, 20), "    1.00 [1.00-1.00]") << unsorted;  // the baseline over itself, every round
  // The block is ordered fastest first; the CSV holds the same medians and intervals.
  const double first = std::stod(o.output.substr(o.output.find("-- quads layers=4, 16x16\n") + 25 + 56, 14));
  const double unsorted_ms = std::stod(unsorted.substr(56, 14)), kbuffer_ms = std::stod(kbuffer.substr(56, 14));
  EXPECT_EQ(first, std::min(unsorted_ms, kbuffer_ms));
  const test::CsvTable table = test::read_csv_table(csv);
  for (const auto& row : table.rows) {
    if (row[table.column("technique")] != "unsorted" || row[table.column("stage")] != "total") continue;
    std::istringstream field(unsorted.substr(56, 14));
    std::string median;
    field >> median;
    EXPECT_EQ(median.rfind(two_decimals(row[table.column("median_ms")]) + "±", 0), 0u) << unsorted;
  }
}

TEST(Cli, BenchWithoutTheBaselineDividesByTheFastestAndSaysSo) {
  const std::string csv = fresh_output("no_baseline.csv");
  const Outcome o = run_oitbench("bench --technique kbuffer --set k=2,4 --scene quads --scene-set layers=4 "
                                 "--size 16x16 --warmup 0 --frames 2 --csv " + csv);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find(" x fastest "), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("(x fastest: unsorted did not run ok here, so ratios are over each block's fastest run)"),
            std::string::npos) << o.output;
  // The first row of the block is the fastest: 1.00.
  const size_t block = o.output.find("-- quads layers=4, 16x16\n");
  ASSERT_NE(block, std::string::npos) << o.output;
  EXPECT_EQ(o.output.substr(block + 25 + 71, 20), "                1.00") << o.output;
}

// Every combination is checked before the first run: a bad value in the
// sweep's last combination fails at once, names the value, writes nothing.
TEST(Cli, BenchValidatesEveryCombinationBeforeTheFirstRun) {
  const std::string csv = fresh_output("never_written.csv");
  const Outcome k = run_oitbench("bench --technique unsorted --technique kbuffer --set k=4,abc --scene quads "
                                 "--size 8x8 --csv " + csv);
  EXPECT_EQ(k.exit_code, 1) << k.output;
  EXPECT_NE(k.output.find("oitbench: error: run 3 of 3 of the sweep: technique 'kbuffer': parameter 'k' = 'abc' "
                          "is not an integer; allowed: integer in [1, 64] or auto (nothing was run)\n"),
            std::string::npos) << k.output;
  EXPECT_EQ(k.output.find("[1/"), std::string::npos) << k.output;
  EXPECT_FALSE(std::filesystem::exists(csv));

  const Outcome scene = run_oitbench("bench --technique unsorted --scene quads --scene-set layers=2,0 --size 8x8 "
                                     "--csv " + csv);
  EXPECT_EQ(scene.exit_code, 1) << scene.output;
  EXPECT_NE(scene.output.find("run 2 of 2 of the sweep: scene 'quads': parameter 'layers' = '0' is out of range"),
            std::string::npos) << scene.output;
  const Outcome unknown = run_oitbench("bench --technique unsorted --scene quads --scene no_such_scene --csv " + csv);
  EXPECT_EQ(unknown.exit_code, 1) << unknown.output;
  EXPECT_NE(unknown.output.find("run 2 of 2 of the sweep: unknown scene 'no_such_scene'"), std::string::npos)
      << unknown.output;
  const Outcome technique = run_oitbench("bench --technique no_such_technique --csv " + csv);
  EXPECT_EQ(technique.exit_code, 1) << technique.output;
  EXPECT_NE(technique.output.find("unknown technique 'no_such_technique'"), std::string::npos) << technique.output;
  EXPECT_FALSE(std::filesystem::exists(csv));
}

// --help shows every default, and the commands that render share one size.
TEST(Cli, HelpShowsEveryDefault) {
  const Outcome bench = run_oitbench("bench --help");
  EXPECT_EQ(bench.exit_code, 0) << bench.output;
  for (const char* expected : {"--precision FLOAT:FLOAT in [0.001 - 1]=0.05", "--min-frames INT:INT in [1 - 100000]=6",
                               "--max-frames INT:INT in [1 - 1000000]=200", "--rounds INT:INT in [1 - 1000]=6",
                               "--warmup INT:INT in [0 - 1000]=1",
                               "--size TEXT=[auto] ...", "-t,--technique TEXT=[all] ...", "-s,--scene TEXT=[quads] ...",
                               "--clock TEXT:{auto,gl,wall,both}=auto", "--baseline TEXT=unsorted",
                               "--camera TEXT=[default] ...", "--background TEXT=0,0,0"})
    EXPECT_NE(bench.output.find(expected), std::string::npos) << expected << "\n" << bench.output;
  const Outcome pareto = run_oitbench("pareto --help");
  EXPECT_NE(pareto.output.find("--size TEXT=[128x128] ..."), std::string::npos) << pareto.output;
  EXPECT_NE(pareto.output.find("smaller than bench's default"), std::string::npos) << pareto.output;
  for (const char* command : {"render", "stats", "adaptive"}) {
    const Outcome help = run_oitbench(std::string(command) + " --help");
    EXPECT_NE(help.output.find("--size TEXT=auto"), std::string::npos) << command << "\n" << help.output;
  }
  const Outcome adaptive = run_oitbench("adaptive --help");
  EXPECT_NE(adaptive.output.find("--repeats INT:INT in [1 - 1000]=2"), std::string::npos) << adaptive.output;
  const Outcome gbench = test::run_command(kOut, std::string(OIT_BINARY_DIR) + "/harness/oitbench_gbench --help");
  EXPECT_NE(gbench.output.find("--size TEXT=[auto] ..."), std::string::npos) << gbench.output;
  EXPECT_NE(gbench.output.find("without it --benchmark_min_time decides"), std::string::npos) << gbench.output;
}

// The wide export: one row per run, every parameter, figure and stage time
// in a column of its own, equal to the long CSV's cells.
TEST(Cli, ExportWideHasAColumnPerParameterFigureAndStage) {
  const std::string csv = fresh_output("long.csv"), wide = fresh_output("wide.csv");
  const Outcome bench = run_oitbench("bench --technique unsorted --technique kbuffer --set k=2,4 --scene quads "
                                     "--scene-set layers=4 --size 16x16 --warmup 0 --frames 2 --clock both --csv " + csv);
  ASSERT_EQ(bench.exit_code, 0) << bench.output;
  const Outcome o = run_oitbench("export --wide " + csv + " -o " + wide);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const test::CsvTable long_form = test::read_csv_table(csv), table = test::read_csv_table(wide);
  EXPECT_NE(o.output.find("3 runs, " + std::to_string(table.header.size()) + " columns -> " + wide), std::string::npos)
      << o.output;
  ASSERT_EQ(table.rows.size(), 3u);
  for (const char* column : {"run_id", "technique", "param.k", "param.tail", "param.auto_k_memory_mb", "scene.layers",
                             "total.wall.median_ms", "total.gl.p95_ms", "fill.wall.median_ms", "error_max"})
    EXPECT_LT(table.column(column), table.header.size()) << column;
  EXPECT_EQ(table.column("stage"), table.header.size());  // folded into the stage columns
  std::set<std::string> ks;
  for (auto row : table.rows) {
    ASSERT_EQ(row.size(), table.header.size());
    row.push_back("<no such column>");  // what table.column() of a missing name reads
    EXPECT_EQ(row[table.column("scene.layers")], "4");
    const bool kbuffer = row[table.column("technique")] == "kbuffer";
    if (kbuffer) ks.insert(row[table.column("param.k")]);
    else EXPECT_EQ(row[table.column("param.k")], "");
    // Every long row of this run: its time under <stage>.<clock>.<time>, its extra figures under extra.<name>.
    size_t matched = 0;
    for (const auto& long_row : long_form.rows) {
      if (long_row[long_form.column("run_id")] != row[table.column("run_id")]) continue;
      ++matched;
      const std::string stage = long_row[long_form.column("stage")] + "." + long_row[long_form.column("clock")];
      for (const char* time : {"median_ms", "min_ms", "p05_ms", "p95_ms", "mean_ms"})
        EXPECT_EQ(row[table.column(stage + "." + time)], long_row[long_form.column(time)]) << stage << time;
      std::istringstream extra(long_row[long_form.column("extra")]);
      for (std::string pair; extra >> pair;)
        EXPECT_EQ(row[table.column("extra." + pair.substr(0, pair.find('=')))], pair.substr(pair.find('=') + 1));
    }
    EXPECT_GE(matched, 4u);  // fill and total (at least), each on both clocks
  }
  EXPECT_EQ(ks, (std::set<std::string>{"2", "4"}));
}

TEST(Cli, ExportOfAMissingCsvIsAnErrorNamingIt) {
  const std::string missing = kOut + "/no_such_results.csv", out = fresh_output("never_wide.csv");
  const Outcome o = run_oitbench("export --wide " + missing + " -o " + out);
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("oitbench: error: results CSV '" + missing + "' does not exist or is empty"),
            std::string::npos) << o.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// pareto sweeps each technique's declared knobs, except one the user's --set
// already names, which keeps the user's values.
TEST(Cli, ParetoSweepsTheDeclaredKnobsUnlessTheUserSetsThem) {
  SweepOptions sweep;
  sweep.techniques = {"kbuffer"};
  const auto& declared = builtin_techniques().get("kbuffer").quality_sweep;
  ASSERT_FALSE(declared.empty());
  const SweepOptions all_knobs = pareto_sweep(sweep, builtin_techniques());
  EXPECT_EQ(all_knobs.technique_sets.size(), declared.size());
  const std::string knob = declared.begin()->first;
  sweep.technique_sets = {knob + "=4"};
  const SweepOptions user = pareto_sweep(sweep, builtin_techniques());
  EXPECT_EQ(user.technique_sets.size(), declared.size());  // the user's set and the other knobs
  EXPECT_EQ(user.technique_sets.front(), knob + "=4");
  for (size_t i = 1; i < user.technique_sets.size(); ++i)
    EXPECT_EQ(user.technique_sets[i].rfind("kbuffer." + knob + "=", 0), std::string::npos) << user.technique_sets[i];
}

// --json: this invocation's runs with the CSV's figures and every frame's
// time; --samples: the same frames as CSV rows.
TEST(Cli, BenchJsonAndSamplesHoldEveryFrameOfTheCsvRuns) {
  const std::string csv = fresh_output("json_runs.csv"), json_path = fresh_output("runs.json"),
                    samples = fresh_output("samples.csv");
  const Outcome o = run_oitbench("bench --technique unsorted --technique kbuffer --set kbuffer.k=4 --scene quads "
                                 "--scene-set layers=4 --size 16x16 --warmup 0 --frames 3 --csv " + csv +
                                 " --json " + json_path + " --samples " + samples);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  std::ifstream in(json_path);
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["device"].get<std::string>().rfind("llvmpipe", 0), 0u) << report["device"];
  ASSERT_EQ(report["runs"].size(), 2u);
  const auto& kbuffer = report["runs"][1];
  EXPECT_EQ(kbuffer["technique"], "kbuffer");
  EXPECT_EQ(kbuffer["params"]["k"], "4");
  EXPECT_EQ(kbuffer["params"]["tail"], "drop");
  EXPECT_EQ(kbuffer["scene_params"]["layers"], "4");
  EXPECT_EQ(kbuffer["status"], "ok");
  EXPECT_EQ(kbuffer["fragments"], 4 * 16 * 16);
  const test::CsvTable table = test::read_csv_table(csv);
  const test::CsvTable frames = test::read_csv_table(samples);
  ASSERT_EQ(frames.header, sample_columns());
  size_t stages = 0;
  for (const auto& run : report["runs"]) {
    for (const auto& stage : run["stages"]) {
      ++stages;
      ASSERT_EQ(stage["samples_ms"].size(), 3u);
      EXPECT_EQ(stage["frames"], 3);
      // The CSV's row of this run and stage holds the same median (to its 6 digits).
      for (const auto& row : table.rows)
        if (row[table.column("run_id")] == run["run_id"] && row[table.column("stage")] == stage["stage"]) {
          EXPECT_NEAR(std::stod(row[table.column("median_ms")]), stage["median_ms"].get<double>(),
                      1e-5 * stage["median_ms"].get<double>());
        }
      size_t frame = 0;
      for (const auto& row : frames.rows)
        if (row[frames.column("run_id")] == run["run_id"] && row[frames.column("stage")] == stage["stage"]) {
          EXPECT_EQ(row[frames.column("frame")], std::to_string(frame));
          EXPECT_NEAR(std::stod(row[frames.column("ms")]), stage["samples_ms"][frame].get<double>(), 1e-6);
          ++frame;
        }
      EXPECT_EQ(frame, 3u) << run["technique"] << " " << stage["stage"];
    }
  }
  EXPECT_EQ(frames.rows.size(), 3 * stages);
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

// The README's promise: oitbench_gbench takes bench's sweep options
// (--frames, --camera among them), and Google Benchmark's own flags decide
// the iterations when --frames does not.
TEST(Cli, GoogleBenchmarkBinaryTakesBenchSweepOptionsAndItsOwnIterationFlags) {
  const std::string gbench = std::string(OIT_BINARY_DIR) + "/harness/oitbench_gbench --benchmark_format=json "
                             "--technique unsorted --scene-set layers=4 --size 16x16 --warmup 0 ";
  auto report_of = [&](const std::string& arguments) {
    const std::string path = fresh_output("gbench_flags.json");
    EXPECT_EQ(std::system((gbench + arguments + " > " + path + " 2>/dev/null").c_str()), 0) << arguments;
    std::ifstream in(path);
    return nlohmann::json::parse(in);
  };
  const nlohmann::json fixed = report_of("--frames 3 --camera random:2:7");
  ASSERT_EQ(fixed["benchmarks"].size(), 2u) << fixed.dump(2);
  EXPECT_EQ(fixed["benchmarks"][0]["name"], "unsorted/scene:quads/layers:4/16x16/camera:random:2:7@0/iterations:3/manual_time");
  EXPECT_EQ(fixed["benchmarks"][1]["name"], "unsorted/scene:quads/layers:4/16x16/camera:random:2:7@1/iterations:3/manual_time");
  for (const auto& run : fixed["benchmarks"]) EXPECT_EQ(run["iterations"], 3);
  // No --frames: --benchmark_min_time asks for more frames than one.
  const nlohmann::json timed = report_of("--benchmark_min_time=0.2");
  ASSERT_EQ(timed["benchmarks"].size(), 1u) << timed.dump(2);
  EXPECT_EQ(timed["benchmarks"][0]["name"], "unsorted/scene:quads/layers:4/16x16/manual_time");
  EXPECT_GT(timed["benchmarks"][0]["iterations"].get<int>(), 1) << timed.dump(2);
  EXPECT_EQ(timed["context"]["timing"], "manual: oitbench's per-frame stage clock total");
  // A bad value fails before anything runs, naming it.
  const test::Outcome bad = test::run_command(kOut, gbench + "--set k=abc --technique kbuffer");
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_NE(bad.output.find("oitbench_gbench: error: run 2 of 2 of the sweep: technique 'kbuffer': parameter 'k' = "
                            "'abc' is not an integer"),
            std::string::npos)
      << bad.output;
}

// ---- issue 40: mistakes that deserve a better answer, and exit statuses ----

TEST(Cli, MistypedNamesGetTheClosestOneSuggested) {
  const std::string csv = fresh_output("never_typo.csv");
  struct Case {
    std::string arguments, expected;
    int exit_code;
  };
  const std::vector<Case> cases = {
      {"benchmark", "oitbench: unknown command 'benchmark'; did you mean bench?", 2},
      {"bench --frame 5 --csv " + csv, "oitbench bench: unknown option '--frame'; did you mean --frames?", 2},
      {"-t kbuffer bench --csv " + csv, "oitbench: -t is an option of a command: give it after the command "
                                        "(oitbench bench -t ...)", 2},
      {"bench -t linked_lsit --csv " + csv, "unknown technique 'linked_lsit'; did you mean linked_list?", 1},
      {"bench -s quadz --csv " + csv, "unknown scene 'quadz'; did you mean quads?", 1},
      {"bench -t kbuffer --set kk=4 --csv " + csv, "--set kk=4: technique 'kbuffer' has no parameter 'kk'; did you "
                                                   "mean k?", 1},
      {"bench --scene-set layrs=4 --csv " + csv, "did you mean layers?", 1},
      {"render -s quads --scene-set layer=3 -o " + kOut + "/never.png", "did you mean layers?", 1},
      {"render -t kbuffer --set tail=blnd -o " + kOut + "/never.png", "did you mean blend?", 1},
      {"adaptive -t kbuffer --feature scene_rct", "did you mean scene_rect?", 1},
      {"bench --clock wal --csv " + csv, "'wal' is not one of auto, gl, wall, both; did you mean wall?", 1},
      {"render --png lineer -o " + kOut + "/never.png", "did you mean linear?", 1},
  };
  for (const Case& c : cases) {
    const Outcome o = run_oitbench(c.arguments);
    EXPECT_EQ(o.exit_code, c.exit_code) << c.arguments << "\n" << o.output;
    EXPECT_NE(o.output.find(c.expected), std::string::npos) << c.arguments << "\n" << o.output;
  }
  EXPECT_FALSE(std::filesystem::exists(csv));
}

TEST(Cli, SetAndSceneSetScopesAreCheckedAndRepeatsRefusedInEveryCommand) {
  const std::string csv = fresh_output("scopes.csv");
  struct Case {
    std::string arguments, expected;
  };
  const std::vector<Case> refused = {
      {"bench --set nosuch.k=4 --csv " + csv, "--set nosuch.k=4: there is no technique 'nosuch'"},
      {"bench -t kbuffer --set linked_list.k=4 --csv " + csv,
       "--set linked_list.k=4: linked_list is not among the selected techniques (kbuffer)"},
      {"bench -t kbuffer --set k=2 --set k=3 --csv " + csv, "give its values as one list: --set k=2,3"},
      {"pareto -t kbuffer --set k=2 --set k=3 --csv " + csv, "give its values as one list: --set k=2,3"},
      {"bench -s quads --scene-set torus.layers=4 --csv " + csv,
       "--scene-set torus.layers=4: torus is not among the selected scenes (quads)"},
      {"bench -s quads --scene-set layers=2 --scene-set layers=3 --csv " + csv, "--scene-set layers=2,3"},
      {"check-order -t kbuffer --set k=2 --set k=3", "--set k is given twice (k=2, k=3); give it once"},
      {"check-order -t kbuffer --set linked_list.max_per_pixel=2",
       "linked_list is not among the selected techniques (kbuffer)"},
      {"check-order -t kbuffer --set kbuffer.k=0", "parameter 'k' = '0' is out of range"},
      {"check-order -s quads --scene-set torus.layers=4", "torus is not among the selected scenes (quads)"},
      {"adaptive -s quads:layers=2,layers=3", "--scene 'quads:layers=2,layers=3': 'layers' is given twice"},
      {"render -t kbuffer --set k=2 --set k=3 -o " + kOut + "/never.png", "--set k is given twice (k=2, k=3); give it once"},
      {"render -t kbuffer --set linked_list.max_per_pixel=2 -o " + kOut + "/never.png",
       "linked_list is not among the selected techniques (kbuffer)"},
      {"render -s quads --scene-set torus.layers=4 -o " + kOut + "/never.png",
       "torus is not among the selected scenes (quads)"},
      {"stats -s quads --scene-set layers=2 --scene-set layers=3", "--scene-set layers is given twice"},
  };
  for (const Case& c : refused) {
    const Outcome o = run_oitbench(c.arguments);
    EXPECT_EQ(o.exit_code, 1) << c.arguments << "\n" << o.output;
    EXPECT_NE(unwrapped(o.output).find(c.expected), std::string::npos) << c.arguments << "\n" << o.output;
  }
  EXPECT_FALSE(std::filesystem::exists(csv));
  // Scoped to quads: torus runs at its defaults (before, torus was refused the key).
  const Outcome scoped = run_oitbench("bench -t unsorted -s quads -s torus --scene-set quads.layers=4 --size 8x8 "
                                      "--frames 1 --warmup 0 --csv " + csv);
  ASSERT_EQ(scoped.exit_code, 0) << scoped.output;
  EXPECT_NE(scoped.output.find("[1/2] unsorted on quads layers=4 8x8 ... "), std::string::npos) << scoped.output;
  EXPECT_NE(scoped.output.find("[2/2] unsorted on torus 8x8 ... "), std::string::npos) << scoped.output;
  // render and stats take scoped keys as bench does.
  const std::string image = fresh_output("scoped_render.pfm");
  const Outcome render = run_oitbench("render -t kbuffer --set kbuffer.k=2 -s quads --scene-set quads.layers=4 "
                                      "--size 8x8 -o " + image);
  ASSERT_EQ(render.exit_code, 0) << render.output;
  EXPECT_NE(render.output.find("kbuffer on quads 8x8 -> " + image + " (max error "), std::string::npos)
      << render.output;
  const Outcome stats = run_oitbench("stats -s quads --scene-set quads.layers=3 --size 8x8");
  ASSERT_EQ(stats.exit_code, 0) << stats.output;
  EXPECT_NE(stats.output.find("depth complexity  max 3,"), std::string::npos) << stats.output;
  // check-order takes --set, scoped like bench's.
  const Outcome order = run_oitbench("check-order -t kbuffer -t unsorted --set kbuffer.k=2 --size 8x8 --seeds 1");
  EXPECT_EQ(order.exit_code, 0) << order.output;
}

TEST(Cli, BaselineMustBeASelectedTechnique) {
  const std::string csv = fresh_output("never_baseline.csv");
  for (const auto& [arguments, expected] : std::vector<std::pair<std::string, std::string>>{
           {"--baseline nosuch", "--baseline 'nosuch' is not a technique id"},
           {"--baseline linked_list:sort=insertion", "is not a technique id; did you mean linked_list?"},
           {"-t kbuffer --baseline linked_list", "--baseline linked_list is not among the selected techniques"}}) {
    const Outcome o = run_oitbench("bench " + arguments + " --csv " + csv);
    EXPECT_EQ(o.exit_code, 1) << arguments << "\n" << o.output;
    EXPECT_NE(unwrapped(o.output).find(expected), std::string::npos) << arguments << "\n" << o.output;
  }
  EXPECT_FALSE(std::filesystem::exists(csv));
}

TEST(Cli, ValuesThatWouldBeSilentlyWrongAreRefusedWithTheReason) {
  const std::string csv = fresh_output("never_values.csv");
  for (const auto& [arguments, expected] : std::vector<std::pair<std::string, std::string>>{
           {"--background -1,0,0", "'-1' is negative: colours are linear"},
           {"--memory-budget ''", "--memory-budget is empty"},
           {"--memory-budget 1e400", "memory size '1e400' is too large"},
           {"--memory-budget 99999999T", "memory size '99999999T' is too large"},
           {"--size 256", "size '256' is not of the form WIDTHxHEIGHT; did you mean 256x256?"},
           {"--scene-set alpha=1e400", "parameter 'alpha' = '1e400' is out of range"}}) {
    const Outcome o = run_oitbench("bench -t unsorted " + arguments + " --csv " + csv);
    EXPECT_EQ(o.exit_code, 1) << arguments << "\n" << o.output;
    EXPECT_NE(unwrapped(o.output).find(expected), std::string::npos) << arguments << "\n" << o.output;
  }
  const Outcome render = run_oitbench("render --memory-budget '' -o " + kOut + "/never.png");
  EXPECT_EQ(render.exit_code, 1) << render.output;
  EXPECT_NE(render.output.find("--memory-budget is empty"), std::string::npos) << render.output;
  EXPECT_FALSE(std::filesystem::exists(csv));
  // 256X256 is a size; --device after the subcommand counts as before it.
  const Outcome upper = run_oitbench("bench --device software -t unsorted --size 8X8 --frames 1 --warmup 0 --csv " +
                                     csv);
  EXPECT_EQ(upper.exit_code, 0) << upper.output;
  EXPECT_NE(upper.output.find("unsorted on quads 8x8 ... "), std::string::npos) << upper.output;
  const Outcome device = run_oitbench("list --device egl:99");
  EXPECT_NE(device.exit_code, 0);
  EXPECT_NE(device.output.find("--device egl:99: this machine has"), std::string::npos) << device.output;
}

// The docs: with CUDA_VISIBLE_DEVICES set, auto takes that GPU or fails,
// and never falls back to llvmpipe. Where the machine has the GPU (CUDA
// device 0), auto renders on it; where it has none (CI), auto fails.
TEST(Cli, CudaVisibleDevicesWithoutItsGpuFailsRatherThanRenderOnSoftware) {
  const Outcome listed = run_oitbench("--device software list");
  ASSERT_EQ(listed.exit_code, 0) << listed.output;
  const std::string out = fresh_output("cuda_visible.png");
  const Outcome automatic = test::run_oitbench(kOut, "render --size 8x8 -o " + out, "CUDA_VISIBLE_DEVICES=0");
  if (listed.output.find(" CUDA device 0") != std::string::npos) {
    EXPECT_EQ(automatic.exit_code, 0) << automatic.output;
    EXPECT_EQ(automatic.output.find("llvmpipe"), std::string::npos) << automatic.output;
    EXPECT_TRUE(std::filesystem::exists(out));
    return;
  }
  EXPECT_EQ(automatic.exit_code, 1) << automatic.output;
  EXPECT_NE(automatic.output.find("CUDA_VISIBLE_DEVICES=0 but no EGL device is its GPU"), std::string::npos)
      << automatic.output;
  EXPECT_NE(automatic.output.find("--device software"), std::string::npos) << automatic.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  const Outcome software =
      test::run_oitbench(kOut, "render --device software --size 8x8 -o " + out, "CUDA_VISIBLE_DEVICES=0");
  EXPECT_EQ(software.exit_code, 0) << software.output;
}

TEST(Cli, ExitStatusesSayWhatWentWrong) {
  // A check that ended in an error is no pass.
  const Outcome order = run_oitbench("check-order -t unsorted -s missing_scene.gltf --size 8x8 --seeds 1");
  EXPECT_EQ(order.exit_code, 3) << order.output;
  EXPECT_NE(order.output.find("error"), std::string::npos) << order.output;
  // A bad scene value is refused before anything runs.
  const Outcome adaptive = run_oitbench("adaptive -t kbuffer -s quads:layers=0");
  EXPECT_EQ(adaptive.exit_code, 1) << adaptive.output;
  EXPECT_NE(adaptive.output.find("--scene 'quads:layers=0': scene 'quads': parameter 'layers' = '0' is out of range"),
            std::string::npos) << adaptive.output;
  // A value an option's own check refuses is a bad value too (1); a malformed command line is 2.
  const Outcome range = run_oitbench("bench --frames 0 --csv " + fresh_output("never_exit.csv"));
  EXPECT_EQ(range.exit_code, 1) << range.output;
  const Outcome missing = run_oitbench("bench");
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("--csv is required"), std::string::npos) << missing.output;
}

TEST(Cli, GoogleBenchmarkBinaryExitsNonZeroWhenNothingOrSomethingFailedRanAndWritesValidJson) {
  const std::string gbench = std::string(OIT_BINARY_DIR) + "/harness/oitbench_gbench --technique unsorted --size 8x8 "
                             "--warmup 0 --frames 2 ";
  const Outcome none = test::run_command(kOut, gbench + "--benchmark_filter=no_such_benchmark");
  EXPECT_EQ(none.exit_code, 1) << none.output;
  EXPECT_NE(none.output.find("--benchmark_filter=no_such_benchmark matches none of the 1 runs"), std::string::npos)
      << none.output;
  const Outcome failed = test::run_command(kOut, gbench + "-s missing_scene.gltf");
  EXPECT_EQ(failed.exit_code, kExitRunsFailed) << failed.output;
  // Repetitions: the cv of unsorted's bytes (0 each time) is 0/0; the JSON must still parse.
  const std::string path = fresh_output("gbench_repetitions.json");
  ASSERT_EQ(std::system((gbench + "--benchmark_repetitions=3 --benchmark_format=json > " + path + " 2>/dev/null")
                            .c_str()),
            0);
  std::ifstream in(path);
  const nlohmann::json report = nlohmann::json::parse(in, nullptr, false);
  ASSERT_FALSE(report.is_discarded()) << "invalid JSON in " << path;
  EXPECT_EQ(report["benchmarks"].size(), 3u + 4u);  // 3 repetitions, then mean, median, stddev, cv
  const Outcome csv = test::run_command(kOut, gbench + "--csv " + kOut + "/never_gbench.csv");
  EXPECT_EQ(csv.exit_code, 1) << csv.output;
  EXPECT_NE(csv.output.find("oitbench_gbench writes no CSV of its own; run `oitbench bench --csv"), std::string::npos)
      << csv.output;
  // GL timer queries on llvmpipe: warned about.
  const Outcome clock = test::run_command(kOut, gbench + "--clock gl");
  EXPECT_EQ(clock.exit_code, 0) << clock.output;
  EXPECT_NE(clock.output.find("warning: --clock gl on llvmpipe"), std::string::npos) << clock.output;
}

}  // namespace
}  // namespace oit
