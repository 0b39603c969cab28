#pragma once
// `oitbench view`: the interactive viewer (GLFW window + Dear ImGui) on top
// of the technique registry and the harness's frame path.
#include <string>
#include <vector>

#include "harness/app/commands.h"

namespace CLI {
class App;
}

namespace oit {

struct ViewOptions {
  std::string technique = "linked_list";
  std::vector<std::string> sets;
  std::string scene = "quads";
  std::vector<std::string> scene_sets;
  std::string size = "512x512";
  std::string background = "0,0,0";
  std::string camera = "default";   // preset; a random:N:SEED set starts at view 0
  std::string compare;              // technique B for the A/B comparison ("" = none)
  std::vector<std::string> compare_sets;
  std::string show = "a";           // a, b or split (A left, B right)
  std::string display = "image";    // image, reference, error, list_length, diagnostic
  std::string diagnostic;           // the technique's diagnostic image to show ("": its first)
  int frames = 0;                   // > 0: render that many frames, then exit
  std::string screenshot;           // PNG of the window after the last frame
  std::string sweep_file = "oitbench_sweep.txt";
  std::string sweep_csv = "results/sweep.csv";
  std::string scene_rect = "on";    // RunSpec::scene_rect of techniques A and B
};

// Registers the subcommand and its options on `app`; returns it.
CLI::App* add_view_command(CLI::App& app, ViewOptions& options);

// Throws std::runtime_error with advice (render/bench or xvfb-run) when no
// display can be opened.
int run_view(const CommonOptions& common, const ViewOptions& options);

}  // namespace oit
