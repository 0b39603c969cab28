#pragma once
// Runs the oitbench binary as users do (a shell command line) for the tests
// of the command line, and splits the CSV lines they check.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace oit::test {

inline const std::string kOitbench = std::string(OIT_BINARY_DIR) + "/harness/oitbench";

struct Outcome {
  int exit_code;
  std::string output;  // stdout and stderr
};

// `environment` is prefixed to the command line (e.g. "OIT_MODEL_DIR=/x").
// The output goes through a log in `out_dir`, one per test process: CTest
// runs the tests of one file in parallel.
inline Outcome run_oitbench(const std::string& out_dir, const std::string& arguments,
                            const std::string& environment = "") {
  std::filesystem::create_directories(out_dir);
  const std::string log = out_dir + "/last_command_" + std::to_string(::getpid()) + ".txt";
  const int status = std::system((environment + " " + kOitbench + " " + arguments + " > " + log + " 2>&1").c_str());
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

// The fields checked by these tests hold no quotes; quoted fields are kept whole.
inline std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) fields.push_back(std::exchange(field, ""));
    else field += c;
  }
  fields.push_back(field);
  return fields;
}

}  // namespace oit::test
