#pragma once
// Runs the oitbench binary as users do (a shell command line) for the tests
// of the command line, and reads the CSV files they check.
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "harness/run/results_csv.h"

namespace oit::test {

inline const std::string kOitbench = std::string(OIT_BINARY_DIR) + "/harness/oitbench";

struct Outcome {
  int exit_code;
  std::string output;  // stdout and stderr
};

// `environment` is prefixed to the command line (e.g. "OIT_MODEL_DIR=/x").
// The output goes through a log in `out_dir`, one per test process: CTest
// runs the tests of one file in parallel.
// run_command: any command line (oitbench_gbench too), gathered the same way.
inline Outcome run_command(const std::string& out_dir, const std::string& command) {
  std::filesystem::create_directories(out_dir);
  const std::string log = out_dir + "/last_command_" + std::to_string(::getpid()) + ".txt";
  const int status = std::system((command + " > " + log + " 2>&1").c_str());
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

inline Outcome run_oitbench(const std::string& out_dir, const std::string& arguments,
                            const std::string& environment = "") {
  return run_command(out_dir, environment + " " + kOitbench + " " + arguments);
}

// A results CSV as the harness reads it (read_csv, libcsv): the header, the
// rows after it, and a column's index by name (header.size() when absent).
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  size_t column(const std::string& name) const {
    return size_t(std::find(header.begin(), header.end(), name) - header.begin());
  }
};

inline CsvTable read_csv_table(const std::string& path) {
  std::vector<std::vector<std::string>> records = read_csv(path);
  CsvTable table;
  if (records.empty()) return table;
  table.header = std::move(records.front());
  table.rows.assign(std::make_move_iterator(records.begin() + 1), std::make_move_iterator(records.end()));
  return table;
}

// A new empty folder `name` under the build's test output folder of `suite`.
inline std::string fresh_dir(const std::string& suite, const std::string& name) {
  const std::string dir = std::string(OIT_BINARY_DIR) + "/test_output/" + suite + "/" + name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// The bytes of a file ("" when it cannot be read).
inline std::string contents_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace oit::test
