#pragma once
// The sweep options of `oitbench bench` and `pareto` and of oitbench_gbench,
// declared once so the three take the same flags with the same meaning, and
// the scene and technique options the other commands share.
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "harness/app/sweep.h"

namespace oit {

// `size_note` follows "repeatable" in --size's help (pareto's says why its
// default is smaller). Defaults come from `sweep` as the caller set it.
inline void add_sweep_cli_options(CLI::App* command, SweepOptions& sweep, const std::string& size_note = "") {
  command->add_option("--technique,-t", sweep.techniques, "technique ids or 'all' (repeatable)");
  command->add_option("--set", sweep.technique_sets,
                      "key=v1,v2 or technique.key=v1,v2: parameter values to sweep (repeatable)");
  command->add_option("--scene,-s", sweep.scenes, "scene ids or files (repeatable)");
  command->add_option("--scene-set", sweep.scene_sets, "scene key=v1,v2 to sweep (repeatable)");
  command->add_option("--size", sweep.sizes,
                      "WIDTHxHEIGHT or auto: the device's default, 256x256 on software GL, 1920x1080 on a GPU "
                      "(repeatable" + size_note + ")");
  command->add_option("--camera", sweep.cameras,
                      "default, random:N:SEED (one run per view), random:N:SEED@I or max_list[:N:SEED] (repeatable)");
  command->add_option("--frames", sweep.frames,
                      "exactly this many timed frames per run, no precision target (default: precision-driven)")
      ->check(CLI::Range(1, 100000));
  command->add_option("--precision", sweep.precision,
                      "stop a run once the 95% interval of its median total is within +-this fraction of it")
      ->check(CLI::Range(0.001, 1.0));
  command->add_option("--min-frames", sweep.min_frames, "timed frames at least, before the precision is judged")
      ->check(CLI::Range(1, 100000));
  command->add_option("--max-frames", sweep.max_frames, "timed frames at most per run")->check(CLI::Range(1, 1000000));
  command->add_option("--max-seconds", sweep.max_seconds, "seconds of timed frames at most per run")
      ->check(CLI::Range(0.001, 1e6));
  command->add_option("--warmup", sweep.warmup, "untimed frames first, at least (shader compilation, caches)")
      ->check(CLI::Range(0, 1000));
  command->add_option("--warmup-ms", sweep.warmup_ms,
                      "untimed frames for at least this long and until the frame time is stable (default: the "
                      "device's, 500 on a GPU, 0 on software GL; see `list`)")
      ->check(CLI::Range(0.0, 600000.0));
  command->add_option("--clock", sweep.clock, "auto, gl, wall or both")
      ->check(CLI::IsMember({"auto", "gl", "wall", "both"}));
  command->add_option("--background", sweep.background, "r,g,b (linear)");
  command->add_option("--scene-rect", sweep.scene_rects,
                      "on, off or on,off: confine techniques to the scene's projected rectangle")
      ->delimiter(',')
      ->check(CLI::IsMember({"on", "off"}));
  command->add_option("--memory-budget", sweep.memory_budget,
                      "storage a technique may use before the frame is rendered in screen tiles, e.g. 512M or 2G "
                      "(default: the device's, see `list`)");
}

// --scene and --scene-set of the commands that take one scene (render,
// check-order, stats, view).
inline void add_scene_cli_options(CLI::App* command, std::string& scene, std::vector<std::string>& scene_sets) {
  command->add_option("--scene,-s", scene, "scene id or .gltf/.glb/.obj/.off/.ply/.stl file");
  command->add_option("--scene-set", scene_sets, "scene parameter key=value (repeatable)");
}

// --technique of the commands that run several techniques in turn
// (adaptive, stress, check-order); `note` follows "repeatable".
inline void add_techniques_cli_option(CLI::App* command, std::vector<std::string>& techniques,
                                      const std::string& note = "") {
  command->add_option("--technique,-t", techniques, "technique ids or 'all' (repeatable" + note + ")");
}

}  // namespace oit
