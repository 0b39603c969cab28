// Files in the wrong place or of the wrong kind (issue #40): outputs of one
// invocation that name the same file, scene files that are FIFOs, devices or
// directories (and the buffers a .gltf names), and the temporary files of
// the atomic writers left by a process killed while writing.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "harness/output/output_file.h"
#include "scenes/scene_library.h"
#include "tests/gl_fixture.h"
#include "tests/oitbench_process.h"

namespace oit {
namespace {

namespace fs = std::filesystem;

std::string fresh_dir(const std::string& name) { return test::fresh_dir("file_faults", name); }

using test::contents_of;

const std::string kBenchOf = "bench --technique unsorted --size 8x8 --frames 1 --warmup 0 --scene ";
const std::string kBench = kBenchOf + "quads";

// ---- one invocation's outputs are distinct files ----

TEST(FileFaults, BenchRefusesAnOutputOptionNamingTheResultsCsvBeforeAnythingRuns) {
  const std::string dir = fresh_dir("same_output");
  const std::string csv = dir + "/runs.csv";
  const auto first = test::run_oitbench(dir, kBench + " --csv " + csv);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const std::string before = contents_of(csv);
  fs::create_symlink(csv, dir + "/link.csv");
  const std::vector<std::pair<std::string, std::string>> clashes = {
      {"--json", csv}, {"--samples", dir + "/./runs.csv"}, {"--json", dir + "/link.csv"}, {"--images", csv}};
  for (const auto& [option, path] : clashes) {
    const auto outcome = test::run_oitbench(dir, kBench + " --csv " + csv + " " + option + " " + path);
    EXPECT_EQ(outcome.exit_code, 1) << outcome.output;
    EXPECT_NE(outcome.output.find("--csv and " + option), std::string::npos) << outcome.output;
    EXPECT_NE(outcome.output.find(path), std::string::npos) << outcome.output;
    EXPECT_EQ(outcome.output.find("rows appended"), std::string::npos) << outcome.output;
    EXPECT_EQ(contents_of(csv), before) << option << " " << path;
  }
  // Two outputs not yet written, one path: refused too, and nothing created.
  const auto outcome = test::run_oitbench(dir, kBench + " --csv " + csv + " --json " + dir + "/a.json --samples " +
                                                   dir + "/sub/../a.json");
  EXPECT_EQ(outcome.exit_code, 1) << outcome.output;
  EXPECT_NE(outcome.output.find("--json and --samples"), std::string::npos) << outcome.output;
  EXPECT_FALSE(fs::exists(dir + "/a.json"));
}

TEST(FileFaults, ExportRefusesToWriteOverTheResultsCsvItReads) {
  const std::string dir = fresh_dir("export_same_file");
  const std::string csv = dir + "/runs.csv";
  ASSERT_EQ(test::run_oitbench(dir, kBench + " --csv " + csv).exit_code, 0);
  const std::string before = contents_of(csv);
  for (const std::string& out : {csv, dir + "/../export_same_file/runs.csv"}) {
    const auto outcome = test::run_oitbench(dir, "export --wide " + csv + " -o " + out);
    EXPECT_EQ(outcome.exit_code, 1) << outcome.output;
    EXPECT_NE(outcome.output.find("--wide and --out"), std::string::npos) << outcome.output;
    EXPECT_NE(outcome.output.find(out), std::string::npos) << outcome.output;
    EXPECT_EQ(contents_of(csv), before);
  }
  EXPECT_EQ(test::run_oitbench(dir, "export --wide " + csv + " -o " + dir + "/wide.csv").exit_code, 0);
}

TEST(FileFaults, DistinctOutputsCompareByFileIdentity) {
  const std::string dir = fresh_dir("identity");
  std::ofstream(dir + "/a.csv") << "x";
  fs::create_hard_link(dir + "/a.csv", dir + "/hard.csv");
  EXPECT_THROW(check_distinct_outputs({{"--csv", dir + "/a.csv"}, {"--json", dir + "/hard.csv"}}),
               std::invalid_argument);
  EXPECT_NO_THROW(check_distinct_outputs({{"--csv", dir + "/a.csv"}, {"--json", dir + "/b.json"}, {"--samples", ""},
                                          {"--images", ""}}));
  EXPECT_NO_THROW(check_distinct_outputs({{"--csv", dir + "/a.csv"}, {"--json", dir + "/a.csv.json"}}));
}

// ---- scene files must be regular files ----

// A FIFO named .glb/.gltf waited forever for a writer in render and bench;
// a directory was "out of host memory", a link to /dev/zero "File is empty".
TEST(FileFaults, AGltfSceneThatIsNotARegularFileIsRefusedByWhatItIs) {
  const std::string dir = fresh_dir("gltf_kinds");
  ASSERT_EQ(mkfifo((dir + "/fifo.glb").c_str(), 0600), 0);
  ASSERT_EQ(mkfifo((dir + "/fifo.gltf").c_str(), 0600), 0);
  fs::create_directory(dir + "/folder.glb");
  fs::create_symlink("/dev/zero", dir + "/zero.gltf");
  const std::vector<std::pair<std::string, std::string>> cases = {{"fifo.glb", "is a FIFO, not a regular file"},
                                                                  {"fifo.gltf", "is a FIFO, not a regular file"},
                                                                  {"folder.glb", "is a directory, not a regular file"},
                                                                  {"zero.gltf", "is a character device, not a regular file"}};
  for (const auto& [name, problem] : cases) {
    const std::string path = dir + "/" + name;
    for (const std::string& command :
         {"render --technique unsorted --size 8x8 --out " + dir + "/out.png --scene " + path,
          kBenchOf + path + " --csv " + dir + "/runs.csv"}) {
      const auto outcome = test::run_oitbench(dir, command, "timeout 60");  // a hang: exit status 124
      EXPECT_NE(outcome.exit_code, 124) << "hung on " << name << ": " << command;
      EXPECT_NE(outcome.output.find(path + ": " + problem), std::string::npos) << outcome.output;
    }
  }
}

// The buffer a .gltf names by URI: a FIFO there hung tinygltf's own lookup.
TEST(FileFaults, AFifoAsTheBufferAGltfNamesIsRefused) {
  const std::string dir = fresh_dir("gltf_buffer_fifo");
  const std::string path = test::write_quads_gltf("file_faults/gltf_buffer_fifo", "quads", {{-1.0f, glm::vec4(0.5f)}});
  ASSERT_TRUE(fs::remove(dir + "/quads.bin"));
  ASSERT_EQ(mkfifo((dir + "/quads.bin").c_str(), 0600), 0);
  const auto outcome = test::run_oitbench(
      dir, "render --technique unsorted --size 8x8 --out " + dir + "/out.png --scene " + path, "timeout 60");
  EXPECT_NE(outcome.exit_code, 124) << "hung on the buffer FIFO";
  EXPECT_EQ(outcome.exit_code, 1) << outcome.output;
  EXPECT_NE(outcome.output.find(dir + "/quads.bin: is a FIFO, not a regular file"), std::string::npos)
      << outcome.output;
}

// ---- temporary files of the atomic writers ----

std::vector<std::string> temporaries_in(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().filename().string().find(".tmp-") != std::string::npos)
      names.push_back(entry.path().filename().string());
  return names;
}

// A child rewrites a large file over and over; SIGTERM (or SIGINT) arrives
// while one of its temporary files exists. The handler removes it and the
// child still ends by that signal.
TEST(FileFaults, ATerminatingSignalRemovesTheTemporaryFileBeingWritten) {
  for (const int signal : {SIGTERM, SIGINT}) {
    const std::string dir = fresh_dir("signal_" + std::to_string(signal));
    const std::string target = dir + "/image.png";
    const pid_t child = fork();
    if (child == 0) {
      const std::string bytes(64 << 20, 'x');
      for (;;) write_file_atomically(target, bytes);
    }
    bool seen = false;
    for (int wait = 0; wait < 20000 && !seen; ++wait) {
      seen = !temporaries_in(dir).empty();
      if (!seen) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    ASSERT_TRUE(seen) << "the writer never made a temporary file";
    ::kill(child, signal);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal) << status;
    EXPECT_EQ(temporaries_in(dir), std::vector<std::string>{}) << "signal " << signal;
  }
}

// A temporary file whose writer died without a handler running (SIGKILL) is
// removed by the next write to the same file; one of a running process is not.
TEST(FileFaults, StaleTemporaryFilesOfDeadWritersAreSweptOnTheNextWrite) {
  const std::string dir = fresh_dir("stale");
  const pid_t dead = fork();
  if (dead == 0) _exit(0);
  ASSERT_EQ(::waitpid(dead, nullptr, 0), dead);  // reaped: its pid names no process now
  const std::string stale = dir + "/.image.png.tmp-" + std::to_string(dead) + "-0";
  const std::string living = dir + "/.image.png.tmp-" + std::to_string(::getppid()) + "-3";
  const std::string other_target = dir + "/.other.png.tmp-" + std::to_string(dead) + "-0";
  const std::string not_a_pid = dir + "/.image.png.tmp-99999999999999999999-0";
  for (const std::string& path : {stale, living, other_target, not_a_pid}) std::ofstream(path) << "partial";
  write_file_atomically(dir + "/image.png", "new");
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(living));
  EXPECT_TRUE(fs::exists(other_target));
  EXPECT_TRUE(fs::exists(not_a_pid));
  EXPECT_EQ(contents_of(dir + "/image.png"), "new");
  // write_new_file_atomically sweeps the same way.
  std::ofstream(dir + "/.new.png.tmp-" + std::to_string(dead) + "-7") << "partial";
  EXPECT_TRUE(write_new_file_atomically(dir + "/new.png", "n"));
  EXPECT_FALSE(fs::exists(dir + "/.new.png.tmp-" + std::to_string(dead) + "-7"));
}

}  // namespace
}  // namespace oit
