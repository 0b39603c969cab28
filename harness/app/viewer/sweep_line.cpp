#include "harness/app/viewer/sweep_line.h"

#include "harness/output/output_file.h"

namespace oit {
namespace {

// Single quotes keep everything literal in a POSIX shell; a single quote
// itself is closed, escaped and reopened.
std::string shell_word(const std::string& word) {
  const bool plain = !word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                             "0123456789_-.,:=/@+") == std::string::npos;
  if (plain) return word;
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

std::string bench_command_line(const ViewConfig& config, const std::string& csv) {
  std::string line = "oitbench bench --technique " + shell_word(config.technique);
  for (const auto& [key, value] : config.params) line += " --set " + shell_word(key + "=" + value);
  line += " --scene " + shell_word(config.scene);
  for (const auto& [key, value] : config.scene_params) line += " --scene-set " + shell_word(key + "=" + value);
  line += " --size " + std::to_string(config.width) + "x" + std::to_string(config.height);
  line += " --camera " + shell_word(config.camera);
  line += " --background " + shell_word(config.background);
  if (!config.scene_rect) line += " --scene-rect off";
  line += " --csv " + shell_word(csv);
  return line;
}

void append_to_sweep_file(const std::string& path, const std::string& line, const std::string& comment) {
  SharedAppendFile file(path);
  const auto lock = file.lock_exclusive();
  file.append((comment.empty() ? "" : "# " + comment + "\n") + line + "\n");
}

}  // namespace oit
