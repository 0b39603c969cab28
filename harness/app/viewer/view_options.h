#pragma once
// What `oitbench view` is asked to show: the command's options
// (view_command.h) and the viewer's configuration (viewer.h). Its own header
// so that neither of those two includes the other for it.
#include <string>
#include <vector>

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

}  // namespace oit
