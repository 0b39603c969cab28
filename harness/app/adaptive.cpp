#include "harness/app/adaptive.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "base/suggest.h"
#include "harness/app/commands.h"
#include "harness/run/results_csv.h"
#include "scenes/scene_library.h"

namespace oit {

const std::vector<std::string> kPresetScenes = {"quads:layers=4", "quads:layers=32", "model:name=engine", "torus"};
const char* const kSceneRectFeature = "scene_rect";

void parse_scene_spec(const std::string& text, std::string& scene, RawParams& params) {
  const auto colon = text.find(':');
  scene = text.substr(0, colon);
  if (scene.empty()) throw std::invalid_argument("--scene '" + text + "' names no scene");
  if (colon == std::string::npos) return;
  std::string rest = text.substr(colon + 1);
  size_t start = 0;
  while (start <= rest.size()) {
    const size_t comma = std::min(rest.find(',', start), rest.size());
    try {
      RawParams one;
      parse_assignment(rest.substr(start, comma - start), one);
      if (params.count(one.begin()->first))
        throw std::invalid_argument("'" + one.begin()->first + "' is given twice; give it once");
      params.insert(*one.begin());
    } catch (const std::exception& e) {
      throw std::invalid_argument("--scene '" + text + "': " + e.what());
    }
    start = comma + 1;
  }
}

namespace {

// One feature of one technique: parameters for on and off, or the harness's
// scene rectangle at the technique's defaults.
struct Feature {
  std::string name;
  RawParams on, off;
  bool harness = false;
};

std::vector<Feature> features_of(const TechniqueDescriptor& t) {
  std::vector<Feature> features;
  for (const auto& s : t.adaptive_switches) features.push_back({s.feature, s.on, s.off, false});
  features.push_back({kSceneRectFeature, {}, {}, true});
  return features;
}

std::vector<const TechniqueDescriptor*> selected_techniques(const AdaptiveOptions& options,
                                                            const TechniqueRegistry& registry) {
  std::vector<const TechniqueDescriptor*> selected;
  auto add = [&](const TechniqueDescriptor& t) {
    if (std::find(selected.begin(), selected.end(), &t) == selected.end()) selected.push_back(&t);
  };
  if (options.techniques.empty()) {
    for (const auto& t : registry.all())
      if (!t.adaptive_switches.empty()) add(t);
  }
  for (const auto& id : options.techniques) {
    if (id == "all") {
      for (const auto& t : registry.all()) add(t);
    } else {
      add(registry.get(id));
    }
  }
  return selected;
}

// The median of every timed frame's total over all repeats of one side.
double median_total(const std::vector<RunResult>& runs) {
  std::vector<double> samples;
  for (const auto& r : runs) {
    if (const StageResult* total = r.total())
      samples.insert(samples.end(), total->samples_ms.begin(), total->samples_ms.end());
  }
  return samples.empty() ? 0.0 : summarize(samples).median;
}

std::string pairs_text(const std::vector<Figure>& pairs) {
  std::string text;
  for (const auto& [name, value, combine] : pairs) {
    char pair[128];
    std::snprintf(pair, sizeof pair, "%s%s=%.10g", text.empty() ? "" : " ", name.c_str(), value);
    text += pair;
  }
  return text;
}

struct Row {
  std::string technique, feature, scene;
  RunStatus status = RunStatus::ok;
  std::string message;
  double on_ms = 0.0, off_ms = 0.0;
  uint64_t on_bytes = 0, off_bytes = 0;
  double difference = 0.0;  // max |on - off| over RGBA
  std::string work_saved;
};

std::string ratio_text(double on, double off) {
  if (off <= 0.0) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", on / off);
  return text;
}

void print_table(const std::vector<Row>& rows) {
  std::printf("\n%-18s %-14s %-20s %10s %10s %7s %12s %12s %7s %10s  %s\n", "technique", "feature", "scene", "on ms",
              "off ms", "time", "on bytes", "off bytes", "memory", "max diff", "work saved (on)");
  for (const auto& r : rows) {
    if (r.status != RunStatus::ok) {
      std::printf("%-18s %-14s %-20s %s: %s\n", r.technique.c_str(), r.feature.c_str(), r.scene.c_str(),
                  to_string(r.status).c_str(), r.message.c_str());
      continue;
    }
    std::printf("%-18s %-14s %-20s %10.2f %10.2f %7s %12llu %12llu %7s %10.3g  %s\n", r.technique.c_str(),
                r.feature.c_str(), r.scene.c_str(), r.on_ms, r.off_ms, ratio_text(r.on_ms, r.off_ms).c_str(),
                static_cast<unsigned long long>(r.on_bytes), static_cast<unsigned long long>(r.off_bytes),
                ratio_text(double(r.on_bytes), double(r.off_bytes)).c_str(), r.difference, r.work_saved.c_str());
  }
}

}  // namespace

int run_adaptive(const CommonOptions& common, const AdaptiveOptions& options) {
  if (options.frames < 1 || options.warmup < 0 || options.repeats < 1)
    throw std::invalid_argument("adaptive needs --frames >= 1, --warmup >= 0 and --repeats >= 1");
  const TechniqueRegistry& registry = builtin_techniques();
  const std::vector<const TechniqueDescriptor*> techniques = selected_techniques(options, registry);
  for (const auto& wanted : options.features) {
    std::vector<std::string> known;
    for (const TechniqueDescriptor* t : techniques)
      for (const Feature& f : features_of(*t))
        if (std::find(known.begin(), known.end(), f.name) == known.end()) known.push_back(f.name);
    if (std::find(known.begin(), known.end(), wanted) == known.end()) {
      std::string list;
      for (const auto& name : known) list += (list.empty() ? "" : ", ") + name;
      throw std::invalid_argument("--feature " + wanted + ": the selected techniques offer " + list +
                                  did_you_mean(wanted, known));
    }
  }
  int width = 0, height = 0;
  parse_size(options.size, width, height);
  const glm::vec3 background = parse_background(options.background);
  const std::vector<std::string>& scenes = options.scenes.empty() ? kPresetScenes : options.scenes;
  std::vector<std::pair<std::string, RawParams>> parsed_scenes;
  for (const auto& text : scenes) {
    parsed_scenes.emplace_back();
    parse_scene_spec(text, parsed_scenes.back().first, parsed_scenes.back().second);
    // A bad scene or value fails here, not as an error line after the other runs.
    try {
      canonical_scene_params(parsed_scenes.back().first, parsed_scenes.back().second);
    } catch (const std::exception& e) {
      throw std::invalid_argument("--scene '" + text + "': " + e.what());
    }
  }

  auto context = create_headless_context(parse_device_choice(common.device), common.debug_gl);
  Harness harness(*context, registry);
  const DeviceProfile& device = harness.device();
  parse_size(size_for(options.size, device), width, height);
  const RunContext csv_context = run_context(device);
  std::unique_ptr<CsvWriter> csv;
  if (!options.csv.empty()) csv = std::make_unique<CsvWriter>(options.csv);
  std::fprintf(stderr, "oitbench adaptive: %zu technique(s), %zu scene(s), %dx%d, %d repeat(s) of on/off on %s\n",
               techniques.size(), scenes.size(), width, height, options.repeats, device.renderer.c_str());

  std::vector<Row> rows;
  for (const TechniqueDescriptor* technique : techniques) {
    for (const Feature& feature : features_of(*technique)) {
      if (!options.features.empty() &&
          std::find(options.features.begin(), options.features.end(), feature.name) == options.features.end())
        continue;
      for (size_t s = 0; s < scenes.size(); ++s) {
        Row row;
        row.technique = technique->id;
        row.feature = feature.name;
        row.scene = scenes[s];
        RunSpec base;
        base.technique = technique->id;
        base.scene = parsed_scenes[s].first;
        base.scene_params = parsed_scenes[s].second;
        base.width = width;
        base.height = height;
        base.frames = options.frames;
        base.warmup = options.warmup;
        base.background = background;
        std::vector<RunResult> on, off;
        // Even repeats run on first, odd ones off first.
        for (int repeat = 0; repeat < options.repeats && row.status == RunStatus::ok; ++repeat) {
          for (int side = 0; side < 2 && row.status == RunStatus::ok; ++side) {
            const bool is_on = (side == 0) == (repeat % 2 == 0);
            RunSpec spec = base;
            if (feature.harness) spec.scene_rect = is_on;
            else spec.params = is_on ? feature.on : feature.off;
            std::fprintf(stderr, "  %s %s=%s on %s (repeat %d) ... ", technique->id.c_str(), feature.name.c_str(),
                         is_on ? "on" : "off", scenes[s].c_str(), repeat + 1);
            RunResult result = harness.run(spec);
            if (csv) csv->write(result, csv_context);
            if (result.status != RunStatus::ok) {
              std::fprintf(stderr, "%s: %s\n", to_string(result.status).c_str(), result.message.c_str());
              row.status = result.status;
              row.message = result.message;
              break;
            }
            std::fprintf(stderr, "%.2f ms\n", result.median_total_ms());
            std::vector<RunResult>& side_runs = is_on ? on : off;
            // Only the last image of each side is compared; drop the others.
            if (!side_runs.empty()) side_runs.back().image = {};
            side_runs.push_back(std::move(result));
          }
        }
        if (row.status == RunStatus::ok) {
          row.on_ms = median_total(on);
          row.off_ms = median_total(off);
          row.on_bytes = on.back().counters.bytes_allocated;
          row.off_bytes = off.back().counters.bytes_allocated;
          row.difference = compare_images(on.back().image, off.back().image).max_abs;
          // The harness's pixels belong to its own feature; a technique's
          // switch shows what the technique reports.
          std::vector<Figure> saved;
          for (const Figure& entry : on.back().counters.work_saved)
            if ((entry.name == kPixelsOutsideSceneRect) == feature.harness) saved.push_back(entry);
          row.work_saved = pairs_text(saved);
        }
        rows.push_back(row);
      }
    }
  }
  print_table(rows);
  std::printf("\ntime and memory: on / off (below 1: the feature saves); max diff: largest |on - off| of any "
              "pixel's RGBA\nmedian total ms over %d timed frames x %d repeats per side | device: %s (%s) | clock: "
              "%s%s%s\n",
              options.frames, options.repeats, device.renderer.c_str(), csv_context.platform.c_str(),
              to_string(harness.default_clock()).c_str(),
              csv ? " | rows appended to " : "", options.csv.c_str());
  // Skipped runs (a model not installed) are fine; a run that failed is not.
  const size_t failed = size_t(std::count_if(rows.begin(), rows.end(),
                                             [](const Row& r) { return r.status == RunStatus::error; }));
  if (failed == 0) return 0;
  std::fprintf(stderr, "oitbench adaptive: %zu feature/scene pair%s ended in an error (the lines above say why)\n",
               failed, failed == 1 ? "" : "s");
  return kExitRunsFailed;
}

}  // namespace oit
