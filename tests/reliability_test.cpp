// Results are never lost or silently corrupted (README "Reliability"): every
// write is checked (a full disk, a link to a device that refuses writes), a
// run is in the CSV whole or not at all, concurrent appenders and --resume
// processes cannot corrupt or repeat each other, and hostile inputs (a FIFO
// named by a parameter, a non-finite background, a damaged cache entry) get
// a clear error or are set right. A "full disk" is a file-size limit
// (RLIMIT_FSIZE) on the writing process: its writes fail part way as on a
// full file system, with no root and no mount needed.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "harness/app/sweep.h"
#include "harness/run/memory_failure.h"
#include "harness/output/output_file.h"
#include "harness/gl/check.h"
#include "harness/run/results_csv.h"
#include "tests/oitbench_process.h"

namespace oit {
namespace {

namespace fs = std::filesystem;
const std::string kOut = std::string(OIT_BINARY_DIR) + "/test_output/reliability";

std::string fresh_dir(const std::string& name) { return test::fresh_dir("reliability", name); }

using test::contents_of;

// `command` through /bin/sh under a resource limit: RLIMIT_FSIZE limits
// every file it writes to `limit` bytes (SIGXFSZ ignored, so writes past it
// fail with EFBIG as they would with ENOSPC on a full disk); RLIMIT_AS its
// address space. Its output comes through a pipe, which no limit cuts.
test::Outcome run_limited(const std::string& command, int resource, rlim_t limit) {
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) return {-1, "no pipe"};
  const pid_t child = fork();
  if (child == 0) {
    dup2(pipe_fds[1], 1);
    dup2(pipe_fds[1], 2);
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    signal(SIGXFSZ, SIG_IGN);
    setenv("OIT_REFERENCE_CACHE", "off", 1);  // only the output under test is written
    const rlimit size{limit, limit};
    setrlimit(resource, &size);
    execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  close(pipe_fds[1]);
  std::string output;
  char block[4096];
  for (ssize_t got; (got = read(pipe_fds[0], block, sizeof block)) != 0;)
    if (got > 0) output.append(block, size_t(got));
    else if (errno != EINTR) break;
  close(pipe_fds[0]);
  int status = 0;
  waitpid(child, &status, 0);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

test::Outcome run_with_file_size_limit(const std::string& command, rlim_t limit) {
  return run_limited(command, RLIMIT_FSIZE, limit);
}

std::vector<std::string> files_in(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

RunContext context() { return {"llvmpipe (LLVM 15.0.6, 256 bits)", "4.5", "egl-surfaceless", "abc1234", "2026-11-22T09:00:00Z"}; }

RunResult six_row_run(const std::string& technique, const std::string& message = "") {
  RunResult r;
  r.spec.technique = technique;
  r.spec.scene = "quads";
  r.spec.width = 16;
  r.spec.height = 16;
  r.technique_params = "k=4";
  r.clock = ClockKind::both;
  for (const char* clock : {"gl", "wall"})
    for (const char* stage : {"fill", "compose", "total"})
      r.stages.push_back({stage, clock, summarize({1.0, 2.0}), {1.0, 2.0}});
  r.error = ImageError{0.0, 0.0, 99.0};
  r.message = message;
  return r;
}

// A fresh results CSV holding a kbuffer run and a linked_list run of six rows each.
std::string csv_of_two_runs(const std::string& name) {
  const std::string csv = fresh_dir(name) + "/runs.csv";
  CsvWriter writer(csv);
  writer.write(six_row_run("kbuffer"), context());
  writer.write(six_row_run("linked_list"), context());
  return csv;
}

// ---- every write is checked ----

TEST(Reliability, ALinkToADeviceRefusingWritesIsAnErrorNamingTheFileForPngAndCsv) {
  const std::string dir = fresh_dir("link_to_device");
  fs::create_symlink("/dev/full", dir + "/out.png");
  fs::create_symlink("/dev/full", dir + "/runs.csv");
  try {
    write_file_atomically(dir + "/out.png", "bytes");
    FAIL() << "a write through a link to /dev/full succeeded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(dir + "/out.png"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("a character device (through a link), not a regular file"),
              std::string::npos)
        << e.what();
  }
  const auto render = test::run_oitbench(dir, "render --technique reference --scene quads --size 8x8 --out " + dir +
                                                  "/out.png");
  EXPECT_NE(render.exit_code, 0);
  EXPECT_NE(render.output.find(dir + "/out.png"), std::string::npos) << render.output;
  const auto bench = test::run_oitbench(
      dir, "bench --technique unsorted --scene quads --size 8x8 --frames 1 --warmup 0 --csv " + dir + "/runs.csv");
  EXPECT_NE(bench.exit_code, 0);
  EXPECT_NE(bench.output.find("cannot append to '" + dir + "/runs.csv': it is a character device"),
            std::string::npos)
      << bench.output;
  EXPECT_TRUE(fs::is_symlink(dir + "/out.png"));  // left as it was
  EXPECT_TRUE(fs::is_symlink(dir + "/runs.csv"));
}

TEST(Reliability, AFullDiskFailsPngAndPfmWithTheFileNamedAndLeavesNothingBehind) {
  const std::string dir = fresh_dir("full_disk_image");
  for (const char* name : {"out.png", "out.pfm"}) {
    const auto limited = run_with_file_size_limit(
        test::kOitbench + " render --technique reference --scene quads --size 64x64 --out " + dir + "/" + name, 100);
    const std::string& output = limited.output;
    EXPECT_NE(limited.exit_code, 0) << output;
    EXPECT_NE(output.find("failed writing '" + dir + "/" + name + "': File too large"), std::string::npos) << output;
    EXPECT_TRUE(files_in(dir).empty()) << "a partial file or temporary stayed: " << files_in(dir).front();
  }
  // An image already there keeps its old content whole.
  std::ofstream(dir + "/out.png") << "old";
  EXPECT_NE(run_with_file_size_limit(
                test::kOitbench + " render --technique reference --scene quads --size 64x64 --out " + dir + "/out.png",
                100)
                .exit_code,
            0);
  EXPECT_EQ(contents_of(dir + "/out.png"), "old");
  EXPECT_EQ(files_in(dir), std::vector<std::string>{"out.png"});
}

TEST(Reliability, BenchImagesOnAFullDiskFailTheBenchInsteadOfLeavingEmptyPngs) {
  const std::string dir = fresh_dir("full_disk_images");
  const std::string csv = dir + "/runs.csv";
  const auto limited = run_with_file_size_limit(
      test::kOitbench + " bench --technique unsorted --scene spheres --size 256x256 --frames 1 --warmup 0 --csv " +
          csv + " --images " + dir + "/images",
      8000);
  const std::string& output = limited.output;
  EXPECT_NE(limited.exit_code, 0) << output;
  EXPECT_NE(output.find("failed writing '" + dir + "/images/unsorted"), std::string::npos) << output;
  EXPECT_NE(output.find("File too large"), std::string::npos) << output;
  for (const auto& name : files_in(dir + "/images")) ADD_FAILURE() << "left behind: " << name;
}

// ---- a run is in the CSV whole or not at all ----

TEST(Reliability, AFullDiskInTheMiddleOfARunLeavesTheCsvAsItWasAndResumeCompletesIt) {
  const std::string dir = fresh_dir("full_disk_csv");
  const std::string csv = dir + "/runs.csv";
  const std::string sweep = " bench --technique unsorted --technique kbuffer --scene quads --size 16x16 --clock both "
                            "--frames 1 --warmup 0 --resume --csv " + csv;
  // The first technique's run goes in whole; the second's rows do not fit.
  const auto first = test::run_oitbench(
      dir, "bench --technique unsorted --scene quads --size 16x16 --clock both --frames 1 --warmup 0 --csv " + csv);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const std::string before = contents_of(csv);
  const auto limited = run_with_file_size_limit(test::kOitbench + sweep, before.size() + 700);
  const std::string& output = limited.output;
  EXPECT_NE(limited.exit_code, 0) << output;
  EXPECT_NE(output.find("failed writing '" + csv + "': File too large"), std::string::npos) << output;
  EXPECT_EQ(contents_of(csv), before) << "part of a run stayed in the CSV";

  const auto resumed = test::run_oitbench(dir, sweep);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("[1/2] unsorted on quads 16x16 ... already in"), std::string::npos) << resumed.output;
  std::vector<std::string> problems;
  const auto finished = finished_runs(parse_csv(contents_of(csv), csv), csv, &problems);
  EXPECT_EQ(finished.size(), 2u);
  EXPECT_TRUE(problems.empty()) << problems.front();
}

TEST(Reliability, ATruncatedCsvIsCutBackToTheLastWholeRunWhichResumeThenIgnores) {
  const std::string csv = csv_of_two_runs("truncated");
  const std::string whole = contents_of(csv);
  const auto contents = parse_csv(whole, csv);
  ASSERT_EQ(contents.records.size(), 13u);
  const uint64_t first_run_end = contents.records[6].end;
  // Cut as a full disk did: 2 of the second run's 6 rows, the second mid-field, no final newline.
  const uint64_t cut = contents.records[8].end - 20;
  fs::resize_file(csv, cut);
  EXPECT_EQ(finished_runs(csv).size(), 1u);  // only the whole run counts, even before a repair
  {
    CsvWriter writer(csv);
    EXPECT_EQ(writer.repair_note(),
              "results CSV '" + csv + "' ended in an incomplete run (lines 8-9, the last cut short without a "
              "newline): cut back to the last complete run (line 7); the " + std::to_string(cut - first_run_end) +
              " bytes cut are kept in '" + csv + ".torn'");
    EXPECT_EQ(contents_of(csv), whole.substr(0, first_run_end));
    EXPECT_EQ(contents_of(csv + ".torn"), whole.substr(first_run_end, cut - first_run_end));
    writer.write(six_row_run("linked_list"), context());  // appended on a clean line end
  }
  EXPECT_EQ(finished_runs(csv).size(), 2u);
  EXPECT_EQ(read_csv(csv).size(), 13u);

  // Cut by hand at a line end: 2 whole lines of a 6-row run are no run either.
  fs::resize_file(csv, parse_csv(contents_of(csv), csv).records[8].end);
  const auto records = parse_csv(contents_of(csv), csv);
  std::vector<std::string> problems;
  EXPECT_EQ(finished_runs(records, csv, &problems).size(), 1u);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("line 8: run '"), std::string::npos) << problems[0];
  EXPECT_NE(problems[0].find("' has 2 row(s) of 6"), std::string::npos) << problems[0];
  CsvWriter repaired(csv);
  EXPECT_NE(repaired.repair_note().find("(lines 8-9): cut back to the last complete run (line 7)"),
            std::string::npos)
      << repaired.repair_note();
  EXPECT_EQ(contents_of(csv), whole.substr(0, first_run_end));
}

TEST(Reliability, AStressCsvWithATornLastRowIsCutBackToItsLastWholeRow) {
  const std::string path = fresh_dir("torn_rows") + "/stress.csv";
  std::ofstream(path, std::ios::binary) << "case,verdict\nfirst,pass\nsecond,\"cut in a quo";
  CsvAppender csv(path, {"case", "verdict"}, "stress CSV");
  EXPECT_EQ(csv.repair_note(), "stress CSV '" + path + "' ended in an incomplete row (line 3, the last cut short "
                               "without a newline): cut back to the last complete row (line 2); the 20 bytes cut "
                               "are kept in '" + path + ".torn'");
  csv.append({{"third", "FAIL"}});
  EXPECT_EQ(contents_of(path), "case,verdict\nfirst,pass\nthird,FAIL\n");
  EXPECT_EQ(contents_of(path + ".torn"), "second,\"cut in a quo");
}

TEST(Reliability, RowsOfTheWrongWidthAreReportedWithLineNumbersAndNeverCount) {
  const std::string csv = csv_of_two_runs("wrong_width");
  const std::string text = contents_of(csv);
  const size_t second_line = text.find('\n') + 1;
  const size_t third_line = text.find('\n', second_line) + 1;
  // Line 3 glued onto a cut line 2, as appends onto a torn line did before.
  std::ofstream(csv, std::ios::binary) << text.substr(0, third_line - 30) << text.substr(third_line);
  CsvWriter writer(csv);
  EXPECT_TRUE(writer.repair_note().empty());  // the damage is not at the end: reported, not cut
  ASSERT_EQ(writer.problems().size(), 2u);
  EXPECT_EQ(writer.problems()[0].rfind("line 2: ", 0), 0u) << writer.problems()[0];
  EXPECT_NE(writer.problems()[0].find(" fields, expected " + std::to_string(csv_columns().size())),
            std::string::npos)
      << writer.problems()[0];
  EXPECT_EQ(writer.problems()[1].rfind("line 3: run '", 0), 0u) << writer.problems()[1];
  EXPECT_NE(writer.problems()[1].find("' has 4 row(s) of 6"), std::string::npos) << writer.problems()[1];
  const auto finished = writer.finished_runs();
  ASSERT_EQ(finished.size(), 1u);
  EXPECT_EQ(finished.begin()->technique, "linked_list");
}

TEST(Reliability, ACrlfCsvIsReadAndAppendedToLikeAnLfOne) {
  const std::string dir = fresh_dir("crlf");
  const std::string csv = dir + "/runs.csv";
  {
    CsvWriter writer(csv);
    writer.write(six_row_run("kbuffer"), context());
  }
  const auto lf_records = read_csv(csv);
  std::string crlf;
  for (char c : contents_of(csv)) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  std::ofstream(csv, std::ios::binary) << crlf;
  EXPECT_EQ(read_csv(csv), lf_records);
  EXPECT_EQ(finished_runs(csv).size(), 1u);
  CsvWriter writer(csv);
  EXPECT_TRUE(writer.problems().empty());
  EXPECT_TRUE(writer.repair_note().empty());
  writer.write(six_row_run("linked_list"), context());
  EXPECT_EQ(read_csv(csv).size(), 13u);
  EXPECT_EQ(writer.finished_runs().size(), 2u);
}

// ---- concurrent writers ----

TEST(Reliability, FourConcurrentAppendersKeepEveryRowWholeFieldByField) {
  const std::string dir = fresh_dir("concurrent");
  const std::string csv = dir + "/runs.csv";
  constexpr int kProcesses = 4, kRuns = 20;
  // Messages of 10 kB, with commas, quotes and newlines: a run is larger
  // than any stream buffer and must still go out as one unit.
  auto message = [](int process, int run) {
    std::string text = "p" + std::to_string(process) + " r" + std::to_string(run) + ": ";
    while (text.size() < 10000) text += "a \"quoted\", line\n";
    return text;
  };
  std::vector<pid_t> children;
  for (int p = 0; p < kProcesses; ++p) {
    const pid_t child = fork();
    if (child == 0) {
      try {
        CsvWriter writer(csv);  // all four race to write the header
        for (int r = 0; r < kRuns; ++r) writer.write(six_row_run("t" + std::to_string(p), message(p, r)), context());
        _exit(0);
      } catch (...) {
        _exit(1);
      }
    }
    children.push_back(child);
  }
  for (pid_t child : children) {
    int status = 0;
    waitpid(child, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  }
  const auto records = read_csv(csv);
  ASSERT_EQ(records.size(), 1u + kProcesses * kRuns * 6u);
  EXPECT_EQ(records[0], csv_columns());
  // Every row equals, field by field, what its run wrote; runs stay in order per process.
  const size_t message_column = size_t(std::find(csv_columns().begin(), csv_columns().end(), "message") -
                                       csv_columns().begin());
  std::map<std::string, int> next_run;
  for (size_t i = 1; i < records.size(); i += 6) {
    const auto& first = records[i];
    ASSERT_EQ(first.size(), csv_columns().size()) << "line " << i + 1;
    const std::string technique = first[5];
    const int process = technique[1] - '0';
    const int run = next_run[technique]++;
    const std::string run_id = first[csv_column("run_id")];
    const auto expected = csv_rows(six_row_run(technique, message(process, run)), context(), run_id);
    for (size_t j = 0; j < 6; ++j) ASSERT_EQ(records[i + j], expected[j]) << "record " << i + j;
    EXPECT_EQ(first[message_column], message(process, run));
  }
  for (int p = 0; p < kProcesses; ++p) EXPECT_EQ(next_run["t" + std::to_string(p)], kRuns);
  EXPECT_EQ(finished_runs(csv).size(), size_t(kProcesses));  // same configuration per process
}

TEST(Reliability, AClaimIsHeldAgainstOtherProcessesUntilDroppedOrTheProcessEnds) {
  const std::string dir = fresh_dir("claims");
  const std::string csv = dir + "/runs.csv";
  const RunKey key{"kbuffer", "k=4", "quads", "", "default", 16, 16};
  RunClaims claims(csv);
  auto other_process_can_claim = [&](const RunKey& k) {
    const pid_t child = fork();
    if (child == 0) {
      RunClaims mine(csv);
      _exit(mine.try_claim(k) ? 0 : 1);
    }
    int status = 0;
    waitpid(child, &status, 0);
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
  };
  {
    const auto claim = claims.try_claim(key);
    ASSERT_TRUE(claim.has_value());
    EXPECT_FALSE(other_process_can_claim(key));
    RunKey other = key;
    other.width = 32;
    EXPECT_TRUE(other_process_can_claim(other));
  }
  EXPECT_TRUE(other_process_can_claim(key));
  EXPECT_EQ(fs::file_size(csv + ".claims"), 0u);
}

TEST(Reliability, TwoResumingBenchesOnOneCsvNeverRunAConfigurationTwice) {
  const std::string dir = fresh_dir("two_resumes");
  const std::string csv = dir + "/runs.csv";
  const std::string sweep = test::kOitbench + " bench --technique unsorted --technique kbuffer --technique "
                            "weighted_blended --scene quads --size 8x8 --size 12x12 --size 16x16 --frames 1 "
                            "--warmup 0 --resume --csv " + csv;
  const std::string command = "(" + sweep + " > " + dir + "/a.log 2>&1 & " + sweep + " > " + dir +
                              "/b.log 2>&1 & wait)";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const auto records = read_csv(csv);
  ASSERT_FALSE(records.empty());
  std::map<std::string, std::set<std::string>> run_ids;  // configuration -> runs
  for (size_t i = 1; i < records.size(); ++i)
    run_ids[records[i][5] + " " + records[i][10] + "x" + records[i][11]].insert(records[i][csv_column("run_id")]);
  EXPECT_EQ(run_ids.size(), 9u);
  for (const auto& [configuration, ids] : run_ids) EXPECT_EQ(ids.size(), 1u) << configuration << " ran twice";
  const std::string logs = contents_of(dir + "/a.log") + contents_of(dir + "/b.log");
  EXPECT_EQ(finished_runs(csv).size(), 9u) << logs;
}

// ---- stress --csv has bench's safeguards ----

TEST(Reliability, StressCsvRefusesAForeignFileAndFailsOnAFullDisk) {
  const std::string dir = fresh_dir("stress_csv");
  const std::string stress = "stress --technique unsorted --case size_1x1 --csv ";
  std::ofstream(dir + "/model.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  {
    CsvWriter writer(dir + "/bench.csv");
    writer.write(six_row_run("kbuffer"), context());
  }
  const std::string bench_before = contents_of(dir + "/bench.csv");
  for (const char* name : {"model.obj", "bench.csv"}) {
    const auto refused = test::run_oitbench(dir, stress + dir + "/" + name);
    EXPECT_NE(refused.exit_code, 0) << refused.output;
    EXPECT_NE(refused.output.find("stress CSV '" + dir + "/" + name + "' exists with different columns"),
              std::string::npos)
        << refused.output;
  }
  EXPECT_EQ(contents_of(dir + "/bench.csv"), bench_before);
  EXPECT_EQ(contents_of(dir + "/model.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");

  const auto first = test::run_oitbench(dir, stress + dir + "/stress.csv");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const std::string before = contents_of(dir + "/stress.csv");
  EXPECT_EQ(read_csv(dir + "/stress.csv").size(), 2u);
  const auto limited =
      run_with_file_size_limit(test::kOitbench + " " + stress + dir + "/stress.csv", before.size() + 10);
  const std::string& output = limited.output;
  EXPECT_NE(limited.exit_code, 0) << output;
  EXPECT_NE(output.find("failed writing '" + dir + "/stress.csv': File too large"), std::string::npos) << output;
  EXPECT_EQ(contents_of(dir + "/stress.csv"), before);
}

// ---- hostile inputs ----

TEST(Reliability, AFifoNamedByAParameterIsRefusedAtOnceNotWaitedOn) {
  const std::string dir = fresh_dir("fifo");
  const std::string fifo = dir + "/transfer.txt";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  for (const std::string& command :
       {"render --technique bucketed_kbuffer --scene quads --size 8x8 --out " + dir + "/out.png",
        "bench --technique bucketed_kbuffer --scene quads --size 8x8 --frames 1 --warmup 0 --csv " + dir +
            "/runs.csv"}) {
    // timeout: a hang would be exit status 124.
    const auto outcome = test::run_oitbench(
        dir, command + " --set opacity_transfer_file=" + fifo, "timeout 60");
    EXPECT_NE(outcome.exit_code, 124) << "hung on the FIFO: " << command;
    EXPECT_NE(outcome.output.find("parameter 'opacity_transfer_file' = '" + fifo +
                                  "' is not a regular file (a FIFO, device or socket)"),
              std::string::npos)
        << outcome.output;
  }
  EXPECT_THROW(require_regular_file(fifo, "scene file"), std::runtime_error);
}

TEST(Reliability, ANonFiniteBackgroundIsRefusedNamingTheOption) {
  for (const std::string value : {"nan,0,0", "0,inf,0", "0,0,-inf"}) {
    try {
      parse_background(value);
      ADD_FAILURE() << value << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("--background '" + value + "'"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("is not a finite number"), std::string::npos) << e.what();
    }
  }
  const auto outcome = test::run_oitbench(
      kOut, "render --technique reference --scene quads --size 8x8 --background nan,0,0 --out " + kOut + "/nan.png");
  EXPECT_NE(outcome.exit_code, 0);
  EXPECT_NE(outcome.output.find("--background 'nan,0,0': 'nan' is not a finite number"), std::string::npos)
      << outcome.output;
  EXPECT_FALSE(fs::exists(kOut + "/nan.png"));
}

TEST(Reliability, MemoryFailuresNameTheSizeWhatRanOutAndWhatToTry) {
  const std::string host = explain_failure(std::bad_alloc(), 8192, 4096);
  EXPECT_EQ(host, "out of host memory at 8192x4096: a host allocation failed (std::bad_alloc). One RGBA32F image of "
                  "this size is 512 MiB, the technique's buffers come on top. Try a smaller --size, or parameters "
                  "that need less memory (a smaller k, fragment pool or bucket count)");
  const std::string device = explain_failure(GlError("GL_OUT_OF_MEMORY during allocating the fragment pool"), 64, 64);
  EXPECT_EQ(device.rfind("out of device memory at 64x64: GL_OUT_OF_MEMORY during allocating the fragment pool. ", 0),
            0u)
      << device;
  EXPECT_EQ(explain_failure(std::runtime_error("scene 'x' not found"), 64, 64), "scene 'x' not found");
  // The real thing: a 4 GiB render target in a 1.8 GiB address space.
  const auto outcome = run_limited("LP_NUM_THREADS=2 " + test::kOitbench +
                                       " render --technique unsorted --scene quads --size 16384x16384 --out " + kOut +
                                       "/huge.png",
                                   RLIMIT_AS, rlim_t(1800) << 20);
  EXPECT_EQ(outcome.exit_code, 1) << outcome.output;
  EXPECT_NE(outcome.output.find("out of device memory at 16384x16384: RGBA32F render target of 16384x16384 is "
                                "incomplete (the device could not allocate it). One RGBA32F image of this size is "
                                "4096 MiB"),
            std::string::npos)
      << outcome.output;
  EXPECT_NE(outcome.output.find("Try a smaller --size"), std::string::npos) << outcome.output;
}

}  // namespace
}  // namespace oit
