// How runs are measured: the median's interval, precision-driven repetition,
// drift and outliers, interleaved rounds and their paired ratios, resolved
// parameters, the GPU clock columns (through a stand-in NVML library) and the
// frame-overhead floor, checked on real bench runs through the CLI.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "harness/run/statistics.h"
#include "tests/gl_fixture.h"
#include "tests/oitbench_process.h"

namespace oit {
namespace {

std::vector<double> ascending(int n) {
  std::vector<double> values;
  for (int i = 1; i <= n; ++i) values.push_back(double(i));
  return values;
}

TEST(Statistics, MedianIntervalIsTheBinomialOrderStatistics) {
  // n = 6: [x_1, x_6] covers the median with 1 - 2/64; [x_2, x_5] only with
  // 1 - 2 * 7/64, under 95%.
  MedianInterval six = median_interval(ascending(6));
  EXPECT_EQ(six.low, 1.0);
  EXPECT_EQ(six.high, 6.0);
  EXPECT_NEAR(six.confidence, 1.0 - 2.0 / 64.0, 1e-12);
  // n = 9: [x_2, x_8] at 1 - 2 * 10/512 (n = 8 would reach only 1 - 2 * 9/256).
  MedianInterval nine = median_interval(ascending(9));
  EXPECT_EQ(nine.low, 2.0);
  EXPECT_EQ(nine.high, 8.0);
  EXPECT_NEAR(nine.confidence, 1.0 - 20.0 / 512.0, 1e-12);
  // n = 5 cannot reach 95%: [min, max] at 1 - 2/32.
  MedianInterval five = median_interval({5, 1, 4, 2, 3});
  EXPECT_EQ(five.low, 1.0);
  EXPECT_EQ(five.high, 5.0);
  EXPECT_NEAR(five.confidence, 0.9375, 1e-12);
  // n = 100: ranks 40 and 61, the textbook interval.
  MedianInterval hundred = median_interval(ascending(100));
  EXPECT_EQ(hundred.low, 40.0);
  EXPECT_EQ(hundred.high, 61.0);
  EXPECT_GE(hundred.confidence, 0.95);
}

TEST(Statistics, PrecisionNeedsTheIntervalAndItsWidth) {
  std::vector<double> tight(30, 10.0);
  tight[0] = 10.1;
  EXPECT_TRUE(precision_reached(summarize(tight), 0.05));
  EXPECT_FALSE(precision_reached(summarize(ascending(30)), 0.05)) << "x_10..x_21 around 15.5 is +-35%";
  EXPECT_FALSE(precision_reached(summarize({10, 10, 10, 10, 10}), 0.05)) << "5 frames never reach 95%";
}

TEST(Statistics, FrameWarningsNameDriftAndOutlyingFrames) {
  std::vector<double> steady;
  for (int i = 0; i < 30; ++i) steady.push_back(10.0 + 0.1 * double(i % 3));
  EXPECT_TRUE(frame_warnings(steady).empty());
  std::vector<double> drifting;
  for (int i = 0; i < 30; ++i) drifting.push_back(9.0 + 0.4 * double(i));
  const auto drift = frame_warnings(drifting);
  ASSERT_EQ(drift.size(), 1u);
  EXPECT_NE(drift[0].find("drift"), std::string::npos) << drift[0];
  std::vector<double> spiky = steady;
  spiky[17] = 90.0;
  const auto spike = frame_warnings(spiky);
  ASSERT_EQ(spike.size(), 1u);
  EXPECT_NE(spike[0].find("1 outlying frame"), std::string::npos) << spike[0];
}

TEST(Statistics, RatioIsPairedByRound) {
  // Each round the host is slower or faster alike: the per-round ratio stays 2.
  std::vector<std::vector<double>> base, twice;
  for (int r = 0; r < 8; ++r) {
    const double speed = 1.0 + 0.5 * double(r % 3);
    base.push_back({10.0 * speed, 10.2 * speed});
    twice.push_back({20.0 * speed, 20.4 * speed});
  }
  const auto ratio = paired_round_ratio(twice, base);
  ASSERT_TRUE(ratio);
  EXPECT_NEAR(ratio->ratio, 2.0, 1e-12);
  EXPECT_NEAR(ratio->interval.low, 2.0, 1e-12);
  EXPECT_NEAR(ratio->interval.high, 2.0, 1e-12);
  EXPECT_EQ(ratio->rounds, 8u);
  EXPECT_FALSE(paired_round_ratio({{}, {}}, {{1.0}, {}}));
}

// The rows of one run's stage (clock wall on llvmpipe) by technique.
std::map<std::string, std::vector<std::string>> total_rows(const test::CsvTable& table) {
  std::map<std::string, std::vector<std::string>> rows;
  for (const auto& row : table.rows)
    if (row[table.column("stage")] == "total") rows[row[table.column("technique")]] = row;
  return rows;
}

// `oitbench bench ARGUMENTS --csv` into a new folder `name`: its output, the
// CSV and its total rows by technique.
struct Bench {
  test::Outcome outcome;
  test::CsvTable table;
  std::map<std::string, std::vector<std::string>> totals;
};
Bench bench(const std::string& name, const std::string& arguments, const std::string& environment = "") {
  const std::string dir = test::fresh_dir("measurement", name);
  Bench run{test::run_oitbench(dir, "bench " + arguments + " --csv " + dir + "/runs.csv", environment), {}, {}};
  if (run.outcome.exit_code == 0) {
    run.table = test::read_csv_table(dir + "/runs.csv");
    run.totals = total_rows(run.table);
  }
  return run;
}

TEST(Measurement, BenchInRoundsRecordsIntervalsRatiosAndResolvedParameters) {
  const Bench run = bench("rounds",
                          "-t unsorted -t linearized_fragment_buffer -t illustration_buffer -s torus --size 64x64 "
                          "--rounds 3 --min-frames 6 --precision 0.5 --max-seconds 20");
  const auto& [outcome, table, rows] = run;
  ASSERT_EQ(outcome.exit_code, 0) << outcome.output;
  ASSERT_EQ(rows.size(), 3u) << outcome.output;
  for (const auto& [technique, row] : rows) {
    SCOPED_TRACE(technique);
    const double median = std::stod(row[table.column("median_ms")]);
    EXPECT_LE(std::stod(row[table.column("ci_low_ms")]), median);
    EXPECT_GE(std::stod(row[table.column("ci_high_ms")]), median);
    EXPECT_GE(std::stoi(row[table.column("frames")]), 6);
    EXPECT_GE(std::stoi(row[table.column("rounds")]), 3) << "6 frames at least, 3 rounds at least: 2 frames per round";
    EXPECT_EQ(row[table.column("precision_reached")], "true");
    EXPECT_GT(std::stod(row[table.column("frame_overhead_ms")]), 0.0);
    EXPECT_EQ(row[table.column("gpu_sm_mhz_start")], "") << "no NVML on software GL";
    // The baseline's own ratio is 1 in every round.
    EXPECT_EQ(row[table.column("baseline")], "unsorted");
    const double ratio = std::stod(row[table.column("ratio")]);
    EXPECT_LE(std::stod(row[table.column("ratio_ci_low")]), ratio);
    EXPECT_GE(std::stod(row[table.column("ratio_ci_high")]), ratio);
    if (technique == "unsorted") {
      EXPECT_EQ(ratio, 1.0);
    }
    // Every frame's time is in the row, in frame order.
    std::istringstream samples(row[table.column("samples_ms")]);
    int count = 0;
    for (double ms; samples >> ms; ++count) EXPECT_GT(ms, 0.0);
    EXPECT_EQ(count, std::stoi(row[table.column("frames")]));
  }
  // What ran, not `auto`: the software rasterizer's paths, named.
  const auto& ib = rows.at("illustration_buffer");
  EXPECT_NE(ib[table.column("requested_params")].find("storage=auto"), std::string::npos);
  EXPECT_NE(ib[table.column("params")].find("storage=arrays_when_even"), std::string::npos);
  EXPECT_NE(ib[table.column("params")].find("diffusion=sweep_where_exact"), std::string::npos);
  EXPECT_NE(ib[table.column("params")].find("sort=array"), std::string::npos) << "sort=auto resolved";
  EXPECT_EQ(ib[table.column("params")].find("=auto"), std::string::npos)
      << "no auto is left: " << ib[table.column("params")];
  const auto& lfb = rows.at("linearized_fragment_buffer");
  EXPECT_NE(lfb[table.column("requested_params")].find("scan=auto"), std::string::npos);
  EXPECT_NE(lfb[table.column("params")].find("scan=host"), std::string::npos);
  EXPECT_EQ(lfb[table.column("params")].find("auto"), std::string::npos) << lfb[table.column("params")];
  // The summary shows the median with its half-width and the paired ratio.
  EXPECT_NE(outcome.output.find("median±95% ms"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("frame overhead floor"), std::string::npos) << outcome.output;
}

TEST(Measurement, ACapEndsARunThatMissesItsPrecision) {
  const Bench run = bench("cap", "-t unsorted -s quads --scene-set layers=2 --size 32x32 --rounds 1 --min-frames 6 "
                                 "--max-frames 9 --precision 0.001");
  const auto& [outcome, table, rows] = run;
  ASSERT_EQ(outcome.exit_code, 0) << outcome.output;
  ASSERT_EQ(rows.size(), 1u);
  const std::vector<std::string> row = rows.at("unsorted");
  EXPECT_EQ(row[table.column("frames")], "9");
  EXPECT_EQ(row[table.column("precision_reached")], "false");
  EXPECT_NE(outcome.output.find("precision 0.001 not reached after 9 frames"), std::string::npos) << outcome.output;
  // --frames fixes the count and sets no precision target.
  const Bench fixed = bench("fixed", "-t unsorted -s quads --scene-set layers=2 --size 32x32 --frames 4");
  ASSERT_EQ(fixed.outcome.exit_code, 0) << fixed.outcome.output;
  const std::vector<std::string> fixed_row = fixed.totals.at("unsorted");
  EXPECT_EQ(fixed_row[fixed.table.column("frames")], "4");
  EXPECT_EQ(fixed_row[fixed.table.column("precision_reached")], "");
}

TEST(Measurement, ClocksFromNvmlAreRecordedAndAMovedClockIsFlagged) {
  // The stand-in NVML reports an SM clock 30% higher at every read.
  const Bench run = bench("nvml", "-t unsorted -s quads --scene-set layers=2 --size 32x32 --frames 3",
                          "OIT_NVML_LIBRARY=" + std::string(OIT_FAKE_NVML));
  const auto& [outcome, table, rows] = run;
  ASSERT_EQ(outcome.exit_code, 0) << outcome.output;
  const std::vector<std::string> row = rows.at("unsorted");
  const int start = std::stoi(row[table.column("gpu_sm_mhz_start")]);
  const int end = std::stoi(row[table.column("gpu_sm_mhz_end")]);
  EXPECT_GT(end, start * 12 / 10);
  EXPECT_EQ(row[table.column("gpu_mem_mhz_start")], "2619");
  EXPECT_EQ(row[table.column("gpu_temp_c_end")], "41");
  EXPECT_EQ(row[table.column("noisy")], "true");
  EXPECT_NE(row[table.column("warnings")].find("the SM clock moved"), std::string::npos)
      << row[table.column("warnings")];
}

}  // namespace
}  // namespace oit

namespace oit {
namespace {

// preset=paper: the technique's published values where the user set nothing,
// an explicit value winning; `requested_params` keeps what was asked for.
TEST(Resolution, PaperPresetSetsThePublishedValuesTheUserLeftOut) {
  const RunResult paper = test::run_ok(test::one_frame("depth_peeling", {{"preset", "paper"}}, "quads", {{"layers", "4"}}, 16));
  EXPECT_NE(paper.technique_params.find("tie_break=submission"), std::string::npos) << paper.technique_params;
  EXPECT_NE(paper.requested_params.find("tie_break=triangle_id"), std::string::npos) << paper.requested_params;
  const RunResult mine = test::run_ok(
      test::one_frame("depth_peeling", {{"preset", "paper"}, {"tie_break", "triangle_id"}}, "quads", {{"layers", "4"}}, 16));
  EXPECT_NE(mine.technique_params.find("tie_break=triangle_id"), std::string::npos) << mine.technique_params;
  const RunResult bkb = test::run_ok(test::one_frame("bucketed_kbuffer", {{"preset", "paper"}}, "quads", {{"layers", "4"}}, 16));
  EXPECT_NE(bkb.technique_params.find("neighbor_search=bucket"), std::string::npos) << bkb.technique_params;
  EXPECT_NE(bkb.technique_params.find("buckets=on"), std::string::npos) << bkb.technique_params;
  // A technique that runs its paper by default has no preset to ask for.
  const RunResult none = test::harness().run(test::one_frame("unsorted", {{"preset", "paper"}}, "quads", {}, 8));
  EXPECT_EQ(none.status, RunStatus::error);
  EXPECT_NE(none.message.find("preset"), std::string::npos) << none.message;
}

}  // namespace
}  // namespace oit
