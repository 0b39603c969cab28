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
#include "harness/app/sweep_cli.h"
#include "harness/app/viewer/view_command.h"
#include "harness/gl/context.h"

namespace {

// The options bench and pareto share: the sweep's (sweep_cli.h) and the
// files and the summary; --help shows each one's default (pareto's differ:
// `size_note` says why).
void add_bench_options(CLI::App* command, oit::BenchOptions& options, const std::string& size_note) {
  oit::add_sweep_cli_options(command, options.sweep, size_note);
  command->add_option("--csv", options.csv, "CSV file to append to")->required();
  command->add_option("--images", options.images_dir,
                      "directory for one sRGB PNG per run (+ _error.png heatmap), named by technique, scene, "
                      "parameters, size and camera; an existing file is never replaced (_2, _3, ... instead)");
  command->add_option("--png", options.png, "display (sRGB of the composite, opaque) or linear (values, alpha = coverage)")
      ->check(CLI::IsMember({"display", "linear"}));
  command->add_flag("--resume", options.resume,
                    "leave out runs that already have an ok or skipped row in the CSV (error rows run again)");
  command->add_option("--samples", options.samples,
                      "CSV file to append every timed frame's stage times to (one row per run, stage, clock, frame)");
  command->add_option("--json", options.json, "JSON file to write this invocation's runs to (samples included)");
  command->add_option("--baseline", options.baseline, "technique whose median total the summary's ratios divide by");
}

}  // namespace

int main(int argc, char** argv) {
  oit::relaunch_with_huge_page_malloc(argv);
  CLI::App app{"oitbench: order-independent transparency techniques, timed stage by stage and compared "
               "with the exact image"};
  app.require_subcommand(1);
  // Every option's default in --help, subcommands included (they copy this).
  app.option_defaults()->always_capture_default();
  oit::CommonOptions common;
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

  auto* list = app.add_subcommand("list", "techniques with their parameters, scenes, device");
  bool list_markdown = false;
  list->add_flag("--markdown", list_markdown, "print only the technique table of the README, from the registry (no GL)");

  oit::RenderOptions render;
  auto* render_cmd = app.add_subcommand("render", "render one image (.png: 8-bit sRGB of the composite, .pfm: linear float RGB)");
  render_cmd->add_option("--technique,-t", render.technique, "technique id (see `list`)");
  render_cmd->add_option("--set", render.sets, "technique parameter key=value (repeatable)");
  render_cmd->add_option("--scene,-s", render.scene, "scene id or .gltf/.glb/.obj/.off/.ply/.stl file");
  render_cmd->add_option("--scene-set", render.scene_sets, "scene parameter key=value (repeatable)");
  render_cmd->add_option("--size", render.size, "WIDTHxHEIGHT");
  render_cmd->add_option("--background", render.background, "r,g,b (linear)");
  render_cmd->add_option("--out,-o", render.out, "output .png or .pfm")->required();
  render_cmd->add_option("--png", render.png, "display (sRGB of the composite, opaque) or linear (values, alpha = coverage)")
      ->check(CLI::IsMember({"display", "linear"}));
  render_cmd->add_option("--camera", render.camera,
                         "default, random:N:SEED (one image per view, _camI), random:N:SEED@I or max_list[:N:SEED]");
  render_cmd->add_option("--scene-rect", render.scene_rect,
                         "on: confine the technique to the scene's projected rectangle; off: full image")
      ->check(CLI::IsMember({"on", "off"}));
  render_cmd->add_option("--memory-budget", render.memory_budget, "storage a technique may use before the frame is rendered in screen tiles, e.g. 512M or 2G (default: the device's, see `list`)");

  oit::BenchOptions bench;
  auto* bench_cmd = app.add_subcommand("bench", "time every combination and append long-form CSV rows");
  add_bench_options(bench_cmd, bench, "");

  // pareto: the bench options, with each technique's quality knobs swept.
  oit::BenchOptions pareto;
  pareto.sweep.scenes = {"quads", "spheres"};
  pareto.sweep.sizes = {"128x128"};
  pareto.sweep.frames = 5;
  auto* pareto_cmd = app.add_subcommand(
      "pareto", "run time against error: bench every technique over its quality knobs (k, max_passes, ...); "
                "plot with analysis/pareto.py");
  // 128x128 and 5 frames: pareto runs every technique at every value of its
  // quality knobs, several times bench's runs; a quarter of the pixels keeps
  // that to minutes on software GL, and the error ranking holds at that size.
  add_bench_options(pareto_cmd, pareto, "; smaller than bench's default: pareto runs every knob value");

  oit::AdaptiveOptions adaptive;
  auto* adaptive_cmd = app.add_subcommand(
      "adaptive", "every adaptive feature (each technique's switches and the harness's scene rectangle) on and off "
                  "on the same scenes: time and memory ratios, image difference, work saved");
  adaptive_cmd->add_option("--technique,-t", adaptive.techniques,
                           "technique ids or 'all' (repeatable; default: those that declare adaptive switches)");
  adaptive_cmd->add_option("--feature", adaptive.features, "only these features, e.g. early_exit, scene_rect (repeatable)");
  adaptive_cmd->add_option("--scene,-s", adaptive.scenes,
                           "ID or ID:key=value,key=value (repeatable; default quads:layers=4, quads:layers=32, "
                           "model:name=engine, torus)");
  adaptive_cmd->add_option("--size", adaptive.size, "WIDTHxHEIGHT");
  adaptive_cmd->add_option("--frames", adaptive.frames, "timed frames per run")->check(CLI::Range(1, 100000));
  adaptive_cmd->add_option("--warmup", adaptive.warmup, "untimed frames first")->check(CLI::Range(0, 1000));
  adaptive_cmd->add_option("--repeats", adaptive.repeats, "on/off pairs per feature and scene, order alternating")
      ->check(CLI::Range(1, 1000));
  adaptive_cmd->add_option("--background", adaptive.background, "r,g,b");
  adaptive_cmd->add_option("--csv", adaptive.csv, "CSV file to append every run to (the columns of bench)");

  oit::StressOptions stress;
  auto* stress_cmd = app.add_subcommand("stress", "numerical and robustness stress cases on every technique: "
                                                   "pass/fail/skip table (each run in its own process)");
  stress_cmd->add_option("--technique,-t", stress.techniques, "technique ids or 'all' (repeatable)");
  stress_cmd->add_flag("--full", stress.full, "every case (default: the reduced set that CI runs)");
  stress_cmd->add_option("--case", stress.case_filter, "only cases whose name contains this text");
  stress_cmd->add_option("--timeout", stress.timeout_s, "seconds per case and technique before it counts as a hang")
      ->check(CLI::Range(1.0, 86400.0));
  stress_cmd->add_option("--csv", stress.csv, "CSV file to append verdicts to");

  oit::CheckOrderOptions order;
  auto* order_cmd = app.add_subcommand("check-order", "how far each technique's image moves when the triangles "
                                                       "are submitted in other orders (exact ones must not)");
  order_cmd->add_option("--technique,-t", order.techniques, "technique ids or 'all' (repeatable)");
  order_cmd->add_option("--scene,-s", order.scene, "scene id or file");
  order_cmd->add_option("--scene-set", order.scene_sets, "scene parameter key=value (repeatable)");
  order_cmd->add_option("--size", order.size,
                        "WIDTHxHEIGHT (smaller than the other commands' default: every technique renders the scene "
                        "in 2N+1 other submission orders, N = --seeds)");
  order_cmd->add_option("--seeds", order.seeds, "shuffled and objects_shuffled seeds 1..N")->check(CLI::Range(1, 100));

  oit::StatsOptions stats;
  auto* stats_cmd = app.add_subcommand("stats", "fragments per pixel of one scene view: triangles, objects, depth "
                                                 "complexity, list-length histogram, Psi, heatmap");
  stats_cmd->add_option("--scene,-s", stats.scene, "scene id or file");
  stats_cmd->add_option("--scene-set", stats.scene_sets, "scene parameter key=value (repeatable)");
  stats_cmd->add_option("--camera", stats.camera, "default, random:N:SEED, random:N:SEED@I or max_list[:N:SEED]");
  stats_cmd->add_option("--size", stats.size, "WIDTHxHEIGHT");
  stats_cmd->add_option("--heatmap", stats.heatmap, "list-length heatmap .png (viridis 0 .. longest, colour bar below)");

  oit::ExportOptions export_options;
  auto* export_cmd = app.add_subcommand(
      "export", "a results CSV as one row per run, every parameter, figure and stage time in its own column");
  export_cmd->add_option("--wide", export_options.wide,
                         "results CSV to export: param.<name>, scene.<name>, extra.<name>, work_saved.<name> and "
                         "<stage>.<clock>.<median|min|p05|p95|mean>_ms columns")
      ->required();
  export_cmd->add_option("--out,-o", export_options.out, "CSV file to write (replaced whole)")->required();

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
    if (*export_cmd) return oit::run_export(export_options);
    if (*view_cmd) return oit::run_view(common, view);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "oitbench: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
