// oitbench: command-line entry point (list, render, bench, view, ...).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <functional>
#include <utility>
#include <vector>

#include "harness/app/adaptive.h"
#include "harness/app/check_order.h"
#include "harness/app/commands.h"
#include "harness/app/doctor.h"
#include "harness/app/huge_page_malloc.h"
#include "harness/app/pareto.h"
#include "harness/app/stress.h"
#include "harness/app/sweep_cli.h"
#include "harness/app/viewer/view_command.h"
#include "harness/output/output_file.h"
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
      ->check(oit::one_of({"display", "linear"}));
  command->add_flag("--resume", options.resume,
                    "leave out runs that already have an ok or skipped row in the CSV (error rows run again)");
  command->add_option("--samples", options.samples,
                      "CSV file to append every timed frame's stage times to (one row per run, stage, clock, frame)");
  command->add_option("--json", options.json, "JSON file to write this invocation's runs to (samples included)");
  command->add_option("--baseline", options.baseline, "technique whose median total the summary's ratios divide by");
  command->add_option("--rounds", options.rounds,
                      "interleave each block's runs in this many rounds at least (A B C, A B C, ...; the ratios "
                      "paired by round, with 95% intervals); 1: each run whole, one after another")
      ->check(CLI::Range(1, 1000));
}

// No output of one bench or pareto invocation may be another (the JSON
// written over the results CSV): refused before anything runs.
void check_distinct_bench_outputs(const oit::BenchOptions& options) {
  oit::check_distinct_outputs({{"--csv", options.csv},
                               {"--json", options.json},
                               {"--samples", options.samples},
                               {"--images", options.images_dir}});
}

// Each command's options live here from parsing to running; `add` registers
// a subcommand with what runs it, so main() is parse-then-dispatch.
struct Commands {
  oit::CommonOptions common;
  bool list_markdown = false;
  std::string list_params;  // `list --markdown --params ID`: that technique's parameter table
  oit::RenderOptions render;
  oit::BenchOptions bench, pareto;
  oit::AdaptiveOptions adaptive;
  oit::StressOptions stress;
  oit::CheckOrderOptions order;
  oit::DoctorOptions doctor;
  oit::StatsOptions stats;
  oit::ExportOptions export_options;
  oit::ViewOptions view;
  std::vector<std::pair<CLI::App*, std::function<int()>>> runs;

  void add(CLI::App* command, std::function<int()> run) { runs.emplace_back(command, std::move(run)); }
};

// --device and --debug-gl go before the subcommand or after it (`oitbench
// bench --device software ...`): every subcommand takes them too, into the
// same options.
void add_common_options(CLI::App& app, Commands& c) {
  std::vector<CLI::App*> commands = app.get_subcommands([](CLI::App*) { return true; });
  commands.insert(commands.begin(), &app);
  for (CLI::App* command : commands) {
    command->add_option("--device", c.common.device,
                        "auto (GPU if present, else software; with CUDA_VISIBLE_DEVICES, as SLURM sets it, that GPU "
                        "or an error), gpu, software, or egl:N (the N-th EGL device `list` prints)")
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
    command->add_flag("--debug-gl", c.common.debug_gl, "create a debug context and print KHR_debug messages");
  }
}

void add_list_command(CLI::App& app, Commands& c) {
  auto* list = app.add_subcommand("list", "techniques with their parameters, scenes, device");
  auto* markdown = list->add_flag("--markdown", c.list_markdown,
                                  "print only the technique table of the README, from the registry (no GL)");
  list->add_option("--params", c.list_params,
                   "with --markdown: print only this technique's parameter table, the one in "
                   "algorithms/ID/README.md")
      ->needs(markdown);
  c.add(list, [&c] {
    if (!c.list_markdown) return oit::run_list(c.common);
    const oit::TechniqueRegistry& registry = oit::builtin_techniques();
    const std::string text = c.list_params.empty()
                                 ? oit::technique_table_markdown(registry)
                                 : oit::technique_params_markdown(registry.get(c.list_params));
    std::fputs(text.c_str(), stdout);
    return 0;
  });
}

void add_render_command(CLI::App& app, Commands& c) {
  oit::RenderOptions& render = c.render;
  auto* cmd = app.add_subcommand("render", "render one image (.png: 8-bit sRGB of the composite, .pfm: linear float RGB)");
  cmd->add_option("--technique,-t", render.technique, "technique id (see `list`)");
  cmd->add_option("--set", render.sets, "technique parameter key=value or technique.key=value (repeatable)");
  oit::add_scene_cli_options(cmd, render.scene, render.scene_sets);
  cmd->add_option("--size", render.size, "WIDTHxHEIGHT");
  cmd->add_option("--background", render.background, "r,g,b (linear)");
  cmd->add_option("--out,-o", render.out, "output .png or .pfm")->required();
  cmd->add_option("--png", render.png, "display (sRGB of the composite, opaque) or linear (values, alpha = coverage)")
      ->check(oit::one_of({"display", "linear"}));
  cmd->add_option("--camera", render.camera,
                  "default, random:N:SEED (one image per view, _camI), random:N:SEED@I or max_list[:N:SEED]");
  cmd->add_option("--scene-rect", render.scene_rect,
                  "on: confine the technique to the scene's projected rectangle; off: full image")
      ->check(oit::one_of({"on", "off"}));
  cmd->add_option("--memory-budget", render.memory_budget,
                  "storage a technique may use before the frame is rendered in screen tiles, e.g. 512M or 2G "
                  "(default: the device's, see `list`)");
  c.add(cmd, [&c] { return oit::run_render(c.common, c.render); });
}

void add_bench_and_pareto_commands(CLI::App& app, Commands& c) {
  auto* bench = app.add_subcommand("bench", "time every combination and append long-form CSV rows");
  add_bench_options(bench, c.bench, "");
  c.add(bench, [&c] {
    check_distinct_bench_outputs(c.bench);
    return oit::run_bench(c.common, c.bench);
  });
  // pareto: the bench options, with each technique's quality knobs swept.
  c.pareto.sweep.scenes = {"quads", "spheres"};
  c.pareto.sweep.sizes = {"128x128"};

  auto* pareto = app.add_subcommand(
      "pareto", "run time against error: bench every technique over its quality knobs (k, max_passes, ...); "
                "plot with analysis/pareto.py");
  // 128x128: pareto runs every technique at every value of its
  // quality knobs, several times bench's runs; a quarter of the pixels keeps
  // that to minutes on software GL, and the error ranking holds at that size.
  add_bench_options(pareto, c.pareto, "; smaller than bench's default: pareto runs every knob value");
  c.add(pareto, [&c] {
    check_distinct_bench_outputs(c.pareto);
    return oit::run_pareto(c.common, c.pareto);
  });
}

void add_adaptive_command(CLI::App& app, Commands& c) {
  oit::AdaptiveOptions& adaptive = c.adaptive;
  auto* cmd = app.add_subcommand(
      "adaptive", "every adaptive feature (each technique's switches and the harness's scene rectangle) on and off "
                  "on the same scenes: time and memory ratios, image difference, work saved");
  oit::add_techniques_cli_option(cmd, adaptive.techniques, "; default: those that declare adaptive switches");
  cmd->add_option("--feature", adaptive.features, "only these features, e.g. early_exit, scene_rect (repeatable)");
  cmd->add_option("--scene,-s", adaptive.scenes,
                  "ID or ID:key=value,key=value (repeatable; default quads:layers=4, quads:layers=32, "
                  "model:name=engine, torus)");
  cmd->add_option("--size", adaptive.size, "WIDTHxHEIGHT");
  cmd->add_option("--frames", adaptive.frames, "timed frames per run")->check(CLI::Range(1, 100000));
  cmd->add_option("--warmup", adaptive.warmup, "untimed frames first")->check(CLI::Range(0, 1000));
  cmd->add_option("--repeats", adaptive.repeats, "on/off pairs per feature and scene, order alternating")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--background", adaptive.background, "r,g,b");
  cmd->add_option("--csv", adaptive.csv, "CSV file to append every run to (the columns of bench)");
  c.add(cmd, [&c] { return oit::run_adaptive(c.common, c.adaptive); });
}

void add_stress_command(CLI::App& app, Commands& c) {
  auto* cmd = app.add_subcommand("stress", "numerical and robustness stress cases on every technique: "
                                            "pass/fail/skip table (each run in its own process)");
  oit::add_techniques_cli_option(cmd, c.stress.techniques);
  cmd->add_flag("--full", c.stress.full, "every case (default: the reduced set that CI runs)");
  cmd->add_option("--case", c.stress.case_filter, "only cases whose name contains this text");
  cmd->add_option("--timeout", c.stress.timeout_s, "seconds per case and technique before it counts as a hang")
      ->check(CLI::Range(1.0, 86400.0));
  cmd->add_option("--csv", c.stress.csv, "CSV file to append verdicts to");
  c.add(cmd, [&c] { return oit::run_stress(c.common, c.stress); });
}

void add_check_order_command(CLI::App& app, Commands& c) {
  auto* cmd = app.add_subcommand("check-order", "how far each technique's image moves when the triangles "
                                                 "are submitted in other orders (exact ones must not)");
  oit::add_techniques_cli_option(cmd, c.order.techniques);
  cmd->add_option("--set", c.order.sets,
                  "key=value or technique.key=value: technique parameter, one value (repeatable)");
  oit::add_scene_cli_options(cmd, c.order.scene, c.order.scene_sets);
  cmd->add_option("--size", c.order.size,
                  "WIDTHxHEIGHT (smaller than the other commands' default: every technique renders the scene "
                  "in 2N+1 other submission orders, N = --seeds)");
  cmd->add_option("--seeds", c.order.seeds, "shuffled and objects_shuffled seeds 1..N")->check(CLI::Range(1, 100));
  c.add(cmd, [&c] { return oit::run_check_order(c.common, c.order); });
}

void add_doctor_command(CLI::App& app, Commands& c) {
  auto* cmd = app.add_subcommand("doctor", "check this device before trusting its numbers: profile, clocks, frame "
                                            "floor, and every exact technique held to its class here (exit 3 if not)");
  oit::add_techniques_cli_option(cmd, c.doctor.techniques, "; the exact ones among them are checked");
  cmd->add_option("--set", c.doctor.technique_sets,
                  "key=value or technique.key=value: a parameter the checks run with (repeatable)");
  cmd->add_option("--size", c.doctor.size, "WIDTHxHEIGHT of every check");
  cmd->add_option("--stress-timeout", c.doctor.stress_timeout_s, "seconds per stress case before it counts as a hang")
      ->check(CLI::Range(1.0, 86400.0));
  c.add(cmd, [&c] { return oit::run_doctor(c.common, c.doctor); });
}

void add_stats_and_export_commands(CLI::App& app, Commands& c) {
  auto* stats = app.add_subcommand("stats", "fragments per pixel of one scene view: triangles, objects, depth "
                                             "complexity, list-length histogram, Psi, heatmap");
  oit::add_scene_cli_options(stats, c.stats.scene, c.stats.scene_sets);
  stats->add_option("--camera", c.stats.camera, "default, random:N:SEED, random:N:SEED@I or max_list[:N:SEED]");
  stats->add_option("--size", c.stats.size, "WIDTHxHEIGHT");
  stats->add_option("--heatmap", c.stats.heatmap, "list-length heatmap .png (viridis 0 .. longest, colour bar below)");
  c.add(stats, [&c] { return oit::run_stats(c.common, c.stats); });
  auto* exports = app.add_subcommand(
      "export", "a results CSV as one row per run, every parameter, figure and stage time in its own column");
  exports->add_option("--wide", c.export_options.wide,
                      "results CSV to export: param.<name>, scene.<name>, extra.<name>, work_saved.<name> and "
                      "<stage>.<clock>.<median|min|p05|p95|mean>_ms columns")
      ->required();
  exports->add_option("--out,-o", c.export_options.out, "CSV file to write (replaced whole)")->required();
  c.add(exports, [&c] {
    oit::check_distinct_outputs({{"--wide", c.export_options.wide}, {"--out", c.export_options.out}});
    return oit::run_export(c.export_options);
  });
}

void add_compare_command(CLI::App& app, Commands& c) {
  auto* compare = app.add_subcommand(
      "compare", "did a change make it faster? compare BASE.csv NEW.csv per configuration and stage (ratio with "
                 "95% interval, U test, verdict), or --builds DIR_A DIR_B -- <bench arguments>; --help lists the rest");
  // Everything after `compare` goes to analysis/compare.py as it is.
  compare->prefix_command();
  compare->set_help_flag();
  c.add(compare, [compare] { return oit::run_compare(compare->remaining()); });
}

// key=value texts of `params`, as run_render and run_stats parse them.
std::vector<std::string> assignments_of(const oit::RawParams& params) {
  std::vector<std::string> texts;
  for (const auto& [key, value] : params) texts.push_back(key + "=" + value);
  return texts;
}

// render and stats read key=value texts themselves: they get them checked
// and resolved as the sweeps' are (scopes, repeats, keys; technique and
// scene named first), the scope taken off.
void resolve_one_value_sets(Commands& c, const CLI::App* command) {
  const oit::TechniqueRegistry& registry = oit::builtin_techniques();
  if (command->get_name() == "render") {
    c.render.sets = assignments_of(
        oit::one_value_technique_params(c.render.sets, {&registry.get(c.render.technique)}, registry).front());
    c.render.scene_sets = assignments_of(oit::one_value_scene_params(c.render.scene_sets, c.render.scene));
  }
  if (command->get_name() == "stats")
    c.stats.scene_sets = assignments_of(oit::one_value_scene_params(c.stats.scene_sets, c.stats.scene));
}

// Checks of bench's and pareto's options that need to know which were
// given; run before anything opens.
void check_bench_options(const CLI::App* command, const oit::BenchOptions& options) {
  oit::refuse_empty_value(command, "--memory-budget", "512M");
  if (command->count("--baseline") > 0)
    oit::validate_baseline(options.baseline, options.sweep.techniques, oit::builtin_techniques());
}

}  // namespace

int main(int argc, char** argv) {
  oit::relaunch_with_huge_page_malloc(argv);
  CLI::App app{"oitbench: order-independent transparency techniques, timed stage by stage and compared "
               "with the exact image"};
  app.require_subcommand(1);
  // Every option's default in --help, subcommands included (they copy this).
  app.option_defaults()->always_capture_default();
  Commands c;
  add_list_command(app, c);
  add_render_command(app, c);
  add_bench_and_pareto_commands(app, c);
  add_adaptive_command(app, c);
  add_stress_command(app, c);
  add_check_order_command(app, c);
  add_doctor_command(app, c);
  add_stats_and_export_commands(app, c);
  add_compare_command(app, c);
  c.add(oit::add_view_command(app, c.view), [&c] { return oit::run_view(c.common, c.view); });
  add_common_options(app, c);  // after the subcommands: each takes them too

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return oit::report_parse_error(app, e, "oitbench", argc, argv);
  }
  try {
    for (const auto& [command, run] : c.runs) {
      if (!*command) continue;
      if (command->get_name() == "render") oit::refuse_empty_value(command, "--memory-budget", "512M");
      resolve_one_value_sets(c, command);
      if (command->get_name() == "bench") check_bench_options(command, c.bench);
      if (command->get_name() == "pareto") check_bench_options(command, c.pareto);
      return run();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "oitbench: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
