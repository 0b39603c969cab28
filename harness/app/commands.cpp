#include "harness/app/commands.h"

#include <cstdio>
#include <iostream>
#include <optional>
#include <set>

#include "harness/app/huge_page_malloc.h"
#include "harness/gl/shader_capabilities.h"
#include "harness/core/heatmap.h"
#include "scenes/cameras.h"
#include "harness/core/results_csv.h"
#include "harness/gl/program_cache.h"
#include "scenes/scene_library.h"
#include "oit_revision.h"

namespace oit {
namespace {

std::unique_ptr<GlContext> open_context(const CommonOptions& common) {
  return create_headless_context(parse_device_choice(common.device), common.debug_gl);
}

void print_params(const ParamSchema& schema) {
  for (const auto& p : schema) {
    std::printf("      %-24s default %-8s %s — %s\n", p.name.c_str(), p.default_value.c_str(), p.range_text().c_str(),
                p.description.c_str());
  }
}

// One line per run; `x baseline` is the run's median total over that of the
// baseline technique's run on the same scene, parameters and size (same run,
// same machine: the only speed comparison worth quoting).
void print_summary(const std::vector<RunResult>& results, const std::string& baseline) {
  std::printf("\n%-18s %-46s %-8s %10s %10s %7s %10s %9s  %s\n", "technique", "params", "status", "total ms",
              ("x " + baseline).c_str(), "passes", "max error", "dropped", "scene | work saved");
  for (const auto& r : results) {
    double base = 0.0;
    for (const auto& b : results)
      if (b.spec.technique == baseline && b.status == RunStatus::ok && b.spec.scene == r.spec.scene &&
          b.scene_params == r.scene_params && b.spec.camera == r.spec.camera && b.spec.width == r.spec.width &&
          b.spec.height == r.spec.height && b.spec.scene_rect == r.spec.scene_rect)
        base = b.median_total_ms();
    const bool ok = r.status == RunStatus::ok;
    char ratio[32] = "";
    if (ok && base > 0.0) std::snprintf(ratio, sizeof ratio, "%.1f", r.median_total_ms() / base);
    const std::string camera = (r.spec.camera == "default" ? "" : " camera " + r.spec.camera) +
                               (r.spec.scene_rect ? "" : " scene_rect off");
    // A scene swept over its parameters (model name=..., quads objects=...)
    // needs them on the line to tell its rows apart.
    bool swept = false;
    for (const auto& o : results) swept |= o.spec.scene == r.spec.scene && o.scene_params != r.scene_params;
    const std::string scene = swept ? r.spec.scene + " " + r.scene_params : r.spec.scene;
    std::string saved;
    for (const Figure& figure : r.counters.work_saved) {
      char pair[96];
      std::snprintf(pair, sizeof pair, " %s=%.10g", figure.name.c_str(), figure.value);
      saved += pair;
    }
    if (!saved.empty()) saved = " |" + saved;
    // Skipped and error runs measured nothing: blanks, not zeros.
    char total[32] = "", passes[32] = "", error[32] = "", dropped[32] = "";
    if (ok) {
      std::snprintf(total, sizeof total, "%.2f", r.median_total_ms());
      std::snprintf(passes, sizeof passes, "%llu", static_cast<unsigned long long>(r.counters.passes));
      std::snprintf(dropped, sizeof dropped, "%llu", static_cast<unsigned long long>(r.counters.fragments_dropped));
      if (r.error) std::snprintf(error, sizeof error, "%.3g", r.error->max_abs);
    }
    std::printf("%-18s %-46s %-8s %10s %10s %7s %10s %9s  %s %dx%d%s%s\n", r.spec.technique.c_str(),
                r.technique_params.c_str(), to_string(r.status).c_str(), total, ratio, passes, error, dropped,
                scene.c_str(), r.spec.width, r.spec.height, camera.c_str(), saved.c_str());
  }
}

}  // namespace

std::string platform_text(const DeviceInfo& device) {
  return device.platform + ", host pages " + host_page_policy() + ", " + atomics_path();
}

RunContext run_context(const DeviceInfo& device) {
  return {device.renderer, device.version, platform_text(device), OIT_GIT_REVISION, utc_timestamp()};
}

std::string technique_table_markdown(const TechniqueRegistry& registry) {
  // Markdown cells end at '|'; none of the registry's texts may hold one.
  auto cell = [](const std::string& text) {
    std::string out;
    for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
  };
  std::string table =
      "| id | technique | paper | kind | parameters (default, range) | stages |\n|---|---|---|---|---|---|\n";
  for (const auto& t : registry.all()) {
    std::string params, stages;
    for (const auto& p : t.params) {
      const std::string default_text = p.default_value.empty() ? "empty" : p.default_value;
      params += (params.empty() ? "" : ", ") + ("`" + p.name + "` (" + default_text + "; " + p.range_text() + ")");
    }
    for (const auto& stage : t.stages) stages += (stages.empty() ? "" : ", ") + stage;
    const std::string kind = t.is_reference ? "exact (the reference)"
                             : t.exactness == Exactness::exact ? "exact"
                                                               : "approximate";
    table += "| `" + t.id + "` | " + cell(t.display_name) + " | " + cell(t.paper) + " | " + kind + " | " +
             cell(params.empty() ? "-" : params) + " | " + stages + " |\n";
  }
  return table;
}

int run_list(const CommonOptions& common) {
  auto context = open_context(common);
  const DeviceInfo& device = context->device();
  std::printf("Device: %s (%s, %s)%s\n\n", device.renderer.c_str(), device.version.c_str(), platform_text(device).c_str(),
              device.software ? " — software GL: stage clock defaults to wall+glFinish" : "");
  const DeviceLimits limits = query_device_limits();
  std::printf("Limits: largest buffer %s (storage block, buffer texture); memory budget %s (%s). A technique whose storage for a frame "
              "exceeds either renders in screen tiles (CSV column `tiles`; --memory-budget sets the budget).\n\n",
              format_bytes(limits.largest_buffer).c_str(), format_bytes(limits.memory_budget).c_str(),
              limits.budget_source.c_str());
  std::printf("EGL devices (--device egl:N):\n");
  for (const auto& line : describe_egl_devices()) std::printf("    %s\n", line.c_str());
  std::printf("\nTechniques:\n");
  for (const auto& t : builtin_techniques().all()) {
    std::string stages;
    for (const auto& s : t.stages) stages += (stages.empty() ? "" : ", ") + s;
    std::printf("  %-20s %s [%s%s]\n      paper: %s\n      stages: %s\n", t.id.c_str(), t.display_name.c_str(),
                t.exactness == Exactness::exact ? "exact" : "approximate", t.is_reference ? ", reference" : "",
                t.paper.c_str(), stages.c_str());
    print_params(t.params);
  }
  std::printf("\nScenes (or a .gltf/.glb/.obj/.off/.ply/.stl file path):\n");
  for (const auto& s : scene_library()) {
    std::printf("  %-20s %s\n", s.id.c_str(), s.description.c_str());
    print_params(s.params);
  }
  return 0;
}

std::string per_view_path(const std::string& out, size_t index) {
  const auto dot = out.find_last_of('.');
  const auto slash = out.find_last_of('/');
  const bool has_extension = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  const std::string suffix = "_cam" + std::to_string(index);
  return has_extension ? out.substr(0, dot) + suffix + out.substr(dot) : out + suffix;
}

namespace {

// "max error X, rmse Y vs reference", or why there is no reference.
std::string error_text(const RunResult& result) {
  if (!result.error) return result.message;
  char text[96];
  std::snprintf(text, sizeof text, "max error %.3g, rmse %.3g vs reference", result.error->max_abs, result.error->rmse);
  return text;
}

}  // namespace

int run_render(const CommonOptions& common, const RenderOptions& options) {
  const std::vector<std::string> cameras = expand_camera_spec(options.camera);
  auto context = open_context(common);
  Harness harness(*context, builtin_techniques());
  for (size_t view = 0; view < cameras.size(); ++view) {
    RunSpec spec;
    spec.technique = options.technique;
    for (const auto& s : options.sets) parse_assignment(s, spec.params);
    spec.scene = options.scene;
    for (const auto& s : options.scene_sets) parse_assignment(s, spec.scene_params);
    spec.camera = cameras[view];
    parse_size(options.size, spec.width, spec.height);
    spec.background = parse_background(options.background);
    spec.scene_rect = parse_on_off("--scene-rect", options.scene_rect);
    if (!options.memory_budget.empty()) spec.memory_budget = parse_memory_size(options.memory_budget);
    spec.warmup = 0;
    spec.frames = 1;
    RunResult result = harness.run(spec);
    if (result.status != RunStatus::ok) {
      std::fprintf(stderr, "oitbench render: %s %s: %s\n", options.technique.c_str(), to_string(result.status).c_str(),
                   result.message.c_str());
      return 1;
    }
    const std::string out = cameras.size() > 1 ? per_view_path(options.out, view) : options.out;
    write_image(result.image, out, parse_png_encoding(options.png));
    std::printf("%s on %s %dx%d%s -> %s (%s)\n", options.technique.c_str(), options.scene.c_str(), spec.width,
                spec.height, spec.camera == "default" ? "" : (" camera " + spec.camera).c_str(), out.c_str(),
                error_text(result).c_str());
  }
  return 0;
}

int run_bench(const CommonOptions& common, const BenchOptions& options) {
  auto context = open_context(common);
  Harness harness(*context, builtin_techniques());
  const std::vector<RunSpec> runs = expand_sweep(options.sweep, builtin_techniques());
  CsvWriter csv(options.csv);  // repairs a torn end first, so only whole runs count
  const std::set<RunKey> finished = options.resume ? csv.finished_runs() : std::set<RunKey>{};
  std::optional<RunClaims> claims;
  if (options.resume) claims.emplace(options.csv);
  const RunContext ctx = run_context(harness.device());
  std::fprintf(stderr, "oitbench bench: %zu runs on %s, clock %s -> %s%s\n", runs.size(),
               harness.device().renderer.c_str(),
               options.sweep.clock == "auto" ? to_string(harness.default_clock()).c_str() : options.sweep.clock.c_str(),
               options.csv.c_str(), options.resume ? " (resuming: runs already there are not run again)" : "");
  std::vector<RunResult> results;
  size_t resumed = 0, elsewhere = 0;
  for (size_t i = 0; i < runs.size(); ++i) {
    const RunSpec& spec = runs[i];
    std::string params;
    for (const auto& [key, value] : spec.params) params += " " + key + "=" + value;
    std::fprintf(stderr, "[%zu/%zu] %s%s on %s %dx%d%s%s ... ", i + 1, runs.size(), spec.technique.c_str(),
                 params.c_str(), spec.scene.c_str(), spec.width, spec.height,
                 spec.camera == "default" ? "" : (" camera " + spec.camera).c_str(),
                 spec.scene_rect ? "" : " scene_rect off");
    const auto key = options.resume ? resume_key(spec, builtin_techniques()) : std::nullopt;
    // Claimed before it runs, then looked up again: another --resume process
    // on this file may have run it meanwhile, or be running it now.
    const auto claim = key && !finished.count(*key) ? claims->try_claim(*key) : std::nullopt;
    if (key && !finished.count(*key) && !claim) {
      std::fprintf(stderr, "being run by another bench --resume on %s, left to it\n", options.csv.c_str());
      ++elsewhere;
      continue;
    }
    if (key && (finished.count(*key) || csv.finished_runs().count(*key))) {
      std::fprintf(stderr, "already in %s, not run again\n", options.csv.c_str());
      ++resumed;
      continue;
    }
    RunResult result = harness.run(spec);
    csv.write(result, ctx);
    if (result.status == RunStatus::ok) {
      std::fprintf(stderr, "%.2f ms, %s%s\n", result.median_total_ms(), error_text(result).c_str(),
                   result.noisy ? " (noisy: other processes were busy)" : "");
      if (result.clock_disagreement && *result.clock_disagreement > 0.10) {
        std::fprintf(stderr, "  warning: gl and wall clocks disagree by %.0f%% on total\n",
                     *result.clock_disagreement * 100.0);
      }
      if (!options.images_dir.empty()) {
        // Never over an earlier file: a name already there gets _2, _3, ...
        const std::string image = write_new_image(result.image, options.images_dir + "/" + run_label(result) + ".png",
                                                  parse_png_encoding(options.png));
        std::string written = image;
        // Where the image is wrong, and how much, on the one scale of every error map.
        if (result.error && result.error->max_abs > 0.0) {
          const Image& reference = harness.reference_image(spec.scene, spec.scene_params, spec.width, spec.height,
                                                           spec.background, spec.camera);
          const std::string stem = image.substr(0, image.size() - 4);  // without ".png"
          written += " " + write_new_image(with_colour_bar(error_heatmap(result.image, reference), error_scale()),
                                           stem + "_error.png");
        }
        std::fprintf(stderr, "  images: %s\n", written.c_str());
      }
    } else {
      std::fprintf(stderr, "%s: %s\n", to_string(result.status).c_str(), result.message.c_str());
    }
    result.image = {};
    results.push_back(std::move(result));
  }
  size_t ok = 0, skipped = 0, failed = 0;
  for (const auto& r : results)
    (r.status == RunStatus::ok ? ok : r.status == RunStatus::skipped ? skipped : failed) += 1;
  if (!results.empty()) print_summary(results, options.baseline);
  if (resumed > 0)
    std::printf("(%zu run%s already in %s from an earlier invocation: not in this table)\n", resumed,
                resumed == 1 ? "" : "s", options.csv.c_str());
  if (elsewhere > 0)
    std::printf("(%zu run%s left to another bench --resume on %s: not in this table)\n", elsewhere,
                elsewhere == 1 ? "" : "s", options.csv.c_str());
  std::printf("\ndevice: %s (%s) | clock: %s | rows appended to %s\n", harness.device().renderer.c_str(),
              platform_text(harness.device()).c_str(),
              options.sweep.clock == "auto" ? to_string(harness.default_clock()).c_str() : options.sweep.clock.c_str(),
              options.csv.c_str());
  std::printf("runs: %zu done (%zu ok, %zu error), %zu resumed (already in the CSV), %zu skipped\n", ok + failed, ok,
              failed, resumed, skipped);
  const ProgramCacheStats programs = ProgramCache::instance().stats();
  std::printf("GL programs: %llu compiled, %llu from the in-process binary cache%s\n",
              static_cast<unsigned long long>(programs.compiled), static_cast<unsigned long long>(programs.reused),
              ProgramCache::instance().enabled() ? "" : " (OIT_PROGRAM_CACHE=off)");
  // Every row is written; a sweep with failed runs still says so to scripts.
  if (failed > 0) {
    std::fprintf(stderr, "oitbench bench: %zu run%s failed (error rows in %s)\n", failed, failed == 1 ? "" : "s",
                 options.csv.c_str());
    return kExitRunsFailed;
  }
  return 0;
}

}  // namespace oit
