#pragma once
// "Add this configuration to a sweep file": the `oitbench bench` command
// line that re-runs what the viewer shows. There is no sweep file format
// that bench reads, so the file is a text file of command lines, one per
// configuration, ready for `sh FILE` (or copying into a script).
#include <string>

#include "base/params.h"

namespace oit {

struct ViewConfig {
  std::string technique;
  RawParams params;        // technique parameters as the user set them
  std::string scene;
  RawParams scene_params;
  int width = 0, height = 0;
  std::string camera = "default";  // a preset spec (scenes/cameras.h)
  std::string background = "0,0,0";
  bool scene_rect = true;  // the harness's scene rectangle (--scene-rect)
};

// `oitbench bench --technique ... --csv CSV`; words that need it are quoted
// for a POSIX shell.
std::string bench_command_line(const ViewConfig& config, const std::string& csv);

// Appends the command line (after a comment line when `comment` is not
// empty) to `path`; throws naming the path when it cannot be written.
void append_to_sweep_file(const std::string& path, const std::string& line, const std::string& comment = "");

}  // namespace oit
