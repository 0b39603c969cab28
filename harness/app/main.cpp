// oitbench: command-line entry point (list, render, bench, view, ...).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

#include "harness/app/adaptive.h"
#include "harness/app/check_order.h"
#include "harness/app/commands.h"
#include "harness/app/huge_page_malloc.h"
#include "harness/app/pareto.h"
#include "harness/app/stress.h"
#include "harness/app/viewer/view_command.h"
#include "harness/gl/context.h"

namespace {

constexpr const char* kMemoryBudgetHelp =
    "storage a technique may use before the frame is rendered in screen tiles, e.g. 512M or 2G (default: see `list`)";

void add_common_options(CLI::App& app, oit::CommonOptions& common) {
  app.add_option("--device", common.device,
                 "auto (GPU if present, else software; with CUDA_VISIBLE_DEVICES, as SLURM sets it, that GPU), gpu, "
                 "software, or egl:N (the N-th EGL device `list` prints)")
      ->check(CLI::Validator(
          [](std::string& text) {
            try {
              oit::parse_device_choice(text);
              return std::string();
            } catch (const std::invalid_argument& e) {
              return std::string(e.what());
            }
          },
          "auto|gpu|software|egl:N"));
  app.add_flag("--debug-gl", common.debug_gl, "create a debug context and print KHR_debug messages");
}

CLI::App* add_render_command(CLI::App& app, oit::RenderOptions& render) {
  auto* command = app.add_subcommand("render", "render one image (.png: 8-bit linear RGBA, .pfm: float RGB)");
  command->add_option("--technique,-t", render.technique, "technique id (see `list`)");
  command->add_option("--set", render.sets, "technique parameter key=value (repeatable)");
  command->add_option("--scene,-s", render.scene, "scene id or .gltf/.glb/.obj/.off/.ply/.stl file");
  command->add_option("--scene-set", render.scene_sets, "scene parameter key=value (repeatable)");
  command->add_option("--size", render.size, "WIDTHxHEIGHT");
  command->add_option("--background", render.background, "r,g,b (linear, default 0,0,0)");
  command->add_option("--out,-o", render.out, "output .png or .pfm")->required();
  command->add_option("--camera", render.camera,
                      "default, random:N:SEED (one image per view, _camI), random:N:SEED@I or max_list[:N:SEED]");
  command->add_option("--scene-rect", render.scene_rect,
                      "on (default): confine the technique to the scene's projected rectangle; off: full image")
      ->check(CLI::IsMember({"on", "off"}));
  command->add_option("--memory-budget", render.memory_budget, kMemoryBudgetHelp);
  return command;
}

// The options bench and pareto share (pareto's defaults differ: the help
// names them after "repeatable").
void add_sweep_options(CLI::App* command, oit::BenchOptions& options, const std::string& scene_default,
                       const std::string& size_default) {
  oit::SweepOptions& sweep = options.sweep;
  command->add_option("--technique,-t", sweep.techniques, "technique ids or 'all' (repeatable)");
  command->add_option("--scene,-s", sweep.scenes, "scene ids or files (repeatable" + scene_default + ")");
  command->add_option("--scene-set", sweep.scene_sets, "scene key=v1,v2 to sweep (repeatable)");
  command->add_option("--size", sweep.sizes, "WIDTHxHEIGHT (repeatable" + size_default + ")");
  command->add_option("--frames", sweep.frames, "timed frames per run")->check(CLI::Range(1, 100000));
  command->add_option("--warmup", sweep.warmup, "untimed frames first (shader compilation)")
      ->check(CLI::Range(0, 1000));
  command->add_option("--memory-budget", sweep.memory_budget, kMemoryBudgetHelp);
  command->add_option("--csv", options.csv, "CSV file to append to")->required();
  command->add_option("--images", options.images_dir, "directory for one PNG per run");
  command->add_flag("--resume", options.resume,
                    "leave out runs that already have an ok or skipped row in the CSV (error rows run again)");
}

CLI::App* add_bench_command(CLI::App& app, oit::BenchOptions& bench) {
  auto* command = app.add_subcommand("bench", "time every combination and append long-form CSV rows");
  add_sweep_options(command, bench, "", "");
  command->add_option("--set", bench.sweep.technique_sets,
                      "key=v1,v2 or technique.key=v1,v2: parameter values to sweep (repeatable)");
  command->add_option("--camera", bench.sweep.cameras,
                      "default, random:N:SEED (one run per view), random:N:SEED@I or max_list[:N:SEED] (repeatable)");
  command->add_option("--clock", bench.sweep.clock, "auto, gl, wall or both")
      ->check(CLI::IsMember({"auto", "gl", "wall", "both"}));
  command->add_option("--background", bench.sweep.background, "r,g,b");
  command->add_option("--scene-rect", bench.sweep.scene_rects,
                      "on (default), off or on,off: confine techniques to the scene's projected rectangle")
      ->delimiter(',')
      ->check(CLI::IsMember({"on", "off"}));
  command->add_option("--baseline", bench.baseline,
                      "technique whose median total the summary divides by (default unsorted)");
  return command;
}

// pareto: the bench options, with each technique's quality knobs swept.
CLI::App* add_pareto_command(CLI::App& app, oit::BenchOptions& pareto) {
  pareto.sweep.scenes = {"quads", "spheres"};
  pareto.sweep.sizes = {"128x128"};
  pareto.sweep.frames = 5;
  auto* command = app.add_subcommand(
      "pareto", "run time against error: bench every technique over its quality knobs (k, max_passes, ...); "
                "plot with analysis/pareto.py");
  add_sweep_options(command, pareto, "; default quads, spheres", "; default 128x128");
  return command;
}

CLI::App* add_adaptive_command(CLI::App& app, oit::AdaptiveOptions& adaptive) {
  auto* command = app.add_subcommand(
      "adaptive", "every adaptive feature (each technique's switches and the harness's scene rectangle) on and off "
                  "on the same scenes: time and memory ratios, image difference, work saved");
  command->add_option("--technique,-t", adaptive.techniques,
                      "technique ids or 'all' (repeatable; default: those that declare adaptive switches)");
  command->add_option("--feature", adaptive.features, "only these features, e.g. early_exit, scene_rect (repeatable)");
  command->add_option("--scene,-s", adaptive.scenes,
                      "ID or ID:key=value,key=value (repeatable; default quads:layers=4, quads:layers=32, "
                      "model:name=engine, torus)");
  command->add_option("--size", adaptive.size, "WIDTHxHEIGHT (default 256x256)");
  command->add_option("--frames", adaptive.frames, "timed frames per run (default 5)")->check(CLI::Range(1, 100000));
  command->add_option("--warmup", adaptive.warmup, "untimed frames first (default 1)")->check(CLI::Range(0, 1000));
  command->add_option("--repeats", adaptive.repeats, "on/off pairs per feature and scene, order alternating (default 2)")
      ->check(CLI::Range(1, 1000));
  command->add_option("--background", adaptive.background, "r,g,b");
  command->add_option("--csv", adaptive.csv, "CSV file to append every run to (the columns of bench)");
  return command;
}

CLI::App* add_stress_command(CLI::App& app, oit::StressOptions& stress) {
  auto* command = app.add_subcommand("stress", "numerical and robustness stress cases on every technique: "
                                               "pass/fail/skip table (each run in its own process)");
  command->add_option("--technique,-t", stress.techniques, "technique ids or 'all' (repeatable)");
  command->add_flag("--full", stress.full, "every case (default: the reduced set that CI runs)");
  command->add_option("--case", stress.case_filter, "only cases whose name contains this text");
  command->add_option("--timeout", stress.timeout_s, "seconds per case and technique before it counts as a hang")
      ->check(CLI::Range(1.0, 86400.0));
  command->add_option("--csv", stress.csv, "CSV file to append verdicts to");
  return command;
}

CLI::App* add_check_order_command(CLI::App& app, oit::CheckOrderOptions& order) {
  auto* command = app.add_subcommand("check-order", "how far each technique's image moves when the triangles "
                                                    "are submitted in other orders (exact ones must not)");
  command->add_option("--technique,-t", order.techniques, "technique ids or 'all' (repeatable)");
  command->add_option("--scene,-s", order.scene, "scene id or file");
  command->add_option("--scene-set", order.scene_sets, "scene parameter key=value (repeatable)");
  command->add_option("--size", order.size, "WIDTHxHEIGHT");
  command->add_option("--seeds", order.seeds, "shuffled and objects_shuffled seeds 1..N")->check(CLI::Range(1, 100));
  return command;
}

CLI::App* add_stats_command(CLI::App& app, oit::StatsOptions& stats) {
  auto* command = app.add_subcommand("stats", "fragments per pixel of one scene view: triangles, objects, depth "
                                              "complexity, list-length histogram, Psi, heatmap");
  command->add_option("--scene,-s", stats.scene, "scene id or file");
  command->add_option("--scene-set", stats.scene_sets, "scene parameter key=value (repeatable)");
  command->add_option("--camera", stats.camera, "default, random:N:SEED, random:N:SEED@I or max_list[:N:SEED]");
  command->add_option("--size", stats.size, "WIDTHxHEIGHT (default 512x512)");
  command->add_option("--heatmap", stats.heatmap, "list-length heatmap .png (blue 0 .. red longest)");
  return command;
}

}  // namespace

int main(int argc, char** argv) {
  oit::relaunch_with_huge_page_malloc(argv);
  CLI::App app{"oitbench: order-independent transparency techniques, timed stage by stage and compared "
               "with the exact image"};
  app.require_subcommand(1);
  oit::CommonOptions common;
  add_common_options(app, common);
  auto* list = app.add_subcommand("list", "techniques with their parameters, scenes, device");
  bool list_markdown = false;
  list->add_flag("--markdown", list_markdown, "print only the technique table of the README, from the registry (no GL)");
  oit::RenderOptions render;
  auto* render_cmd = add_render_command(app, render);
  oit::BenchOptions bench;
  auto* bench_cmd = add_bench_command(app, bench);
  oit::BenchOptions pareto;
  auto* pareto_cmd = add_pareto_command(app, pareto);
  oit::AdaptiveOptions adaptive;
  auto* adaptive_cmd = add_adaptive_command(app, adaptive);
  oit::StressOptions stress;
  auto* stress_cmd = add_stress_command(app, stress);
  oit::CheckOrderOptions order;
  auto* order_cmd = add_check_order_command(app, order);
  oit::StatsOptions stats;
  auto* stats_cmd = add_stats_command(app, stats);
  oit::ViewOptions view;
  auto* view_cmd = oit::add_view_command(app, view);

  CLI11_PARSE(app, argc, argv);
  try {
    if (*list && list_markdown) {
      std::fputs(oit::technique_table_markdown(oit::builtin_techniques()).c_str(), stdout);
      return 0;
    }
    if (*list) return oit::run_list(common);
    if (*render_cmd) return oit::run_render(common, render);
    if (*bench_cmd) return oit::run_bench(common, bench);
    if (*stress_cmd) return oit::run_stress(common, stress);
    if (*adaptive_cmd) return oit::run_adaptive(common, adaptive);
    if (*pareto_cmd) return oit::run_pareto(common, pareto);
    if (*order_cmd) return oit::run_check_order(common, order);
    if (*stats_cmd) return oit::run_stats(common, stats);
    if (*view_cmd) return oit::run_view(common, view);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "oitbench: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
