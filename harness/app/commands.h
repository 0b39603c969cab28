#pragma once
#include <string>
#include <vector>

#include "app/sweep.h"

namespace oit {

struct CommonOptions {
  std::string device = "auto";
  bool debug_gl = false;
};

struct RenderOptions {
  std::string technique = "reference";
  std::vector<std::string> sets;
  std::string scene = "quads";
  std::vector<std::string> scene_sets;
  std::string size = "256x256";
  std::string out;
  std::string background = "0,0,0";
};

struct BenchOptions {
  SweepOptions sweep;
  std::string csv;
  std::string images_dir;  // one PNG per run when set
  std::string baseline = "unsorted";  // the summary's speed ratios are against this technique
};

int run_list(const CommonOptions& common);
int run_render(const CommonOptions& common, const RenderOptions& options);
int run_bench(const CommonOptions& common, const BenchOptions& options);

}  // namespace oit
