#include "harness/app/sweep.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <set>
#include <sstream>
#include <stdexcept>

#include "scenes/cameras.h"
#include "scenes/scene_library.h"

namespace oit {
namespace {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (parts.empty()) parts.push_back("");
  return parts;
}

struct Assignment {
  std::string scope;  // technique id, or "" for every technique that has the key
  std::string key;
  std::vector<std::string> values;
};

Assignment parse_sweep_assignment(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) throw std::invalid_argument("'" + text + "' is not of the form key=value");
  Assignment a;
  a.key = text.substr(0, eq);
  if (const auto dot = a.key.find('.'); dot != std::string::npos) {
    a.scope = a.key.substr(0, dot);
    a.key = a.key.substr(dot + 1);
  }
  a.values = split(text.substr(eq + 1), ',');
  return a;
}

// Cartesian product of the assignments as raw parameter maps.
std::vector<RawParams> combinations(const std::vector<Assignment>& assignments) {
  std::vector<RawParams> result{RawParams{}};
  for (const auto& a : assignments) {
    std::vector<RawParams> next;
    for (const auto& partial : result) {
      for (const auto& value : a.values) {
        RawParams p = partial;
        p[a.key] = value;
        next.push_back(p);
      }
    }
    result = std::move(next);
  }
  return result;
}

bool has_param(const TechniqueDescriptor& t, const std::string& key) {
  return std::any_of(t.params.begin(), t.params.end(), [&](const ParamSpec& s) { return s.name == key; });
}

}  // namespace

void apply_repetition(const SweepOptions& options, RunSpec& spec) {
  spec.warmup = options.warmup;
  spec.warmup_ms = options.warmup_ms < 0.0 ? options.auto_warmup_ms : options.warmup_ms;
  if (options.frames > 0) {
    spec.frames = options.frames;
    spec.precision = 0.0;
    return;
  }
  spec.frames = options.min_frames;
  spec.precision = options.precision;
  spec.max_frames = std::max(options.max_frames, options.min_frames);
  spec.max_seconds = options.max_seconds;
}

std::string size_for(const std::string& text, const DeviceProfile& device) {
  return text == "auto" ? device.default_size : text;
}

void parse_size(const std::string& given, int& width, int& height) {
  // Before the device is known (validation), auto stands for the smallest default.
  const std::string text = given == "auto" ? "256x256" : given;
  const auto x = text.find('x');
  try {
    if (x == std::string::npos) throw std::invalid_argument("");
    size_t used_w = 0, used_h = 0;
    width = std::stoi(text.substr(0, x), &used_w);
    height = std::stoi(text.substr(x + 1), &used_h);
    if (used_w != x || used_h != text.size() - x - 1) throw std::invalid_argument("");
  } catch (const std::exception&) {
    throw std::invalid_argument("size '" + text + "' is not of the form WIDTHxHEIGHT");
  }
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw std::invalid_argument("size '" + text + "' is outside 1x1 .. 16384x16384");
}

glm::vec3 parse_background(const std::string& text) {
  const auto parts = split(text, ',');
  if (parts.size() != 3) throw std::invalid_argument("background '" + text + "' must be r,g,b");
  glm::vec3 color;
  for (int i = 0; i < 3; ++i) {
    try {
      size_t used = 0;
      color[i] = std::stof(parts[size_t(i)], &used);
      if (used != parts[size_t(i)].size() || !std::isfinite(color[i])) throw std::invalid_argument("");
    } catch (const std::exception&) {
      // nan or inf would turn every error metric into nonsense.
      throw std::invalid_argument("--background '" + text + "': '" + parts[size_t(i)] + "' is not a finite number");
    }
  }
  return color;
}

bool parse_on_off(const std::string& option, const std::string& text) {
  if (text == "on") return true;
  if (text == "off") return false;
  throw std::invalid_argument(option + " '" + text + "' must be on or off");
}

std::vector<RunSpec> expand_sweep(const SweepOptions& options, const TechniqueRegistry& registry) {
  std::vector<const TechniqueDescriptor*> techniques;
  for (const auto& id : options.techniques) {
    if (id == "all") {
      for (const auto& t : registry.all())
        if (std::find(techniques.begin(), techniques.end(), &t) == techniques.end()) techniques.push_back(&t);
    } else {
      techniques.push_back(&registry.get(id));
    }
  }
  std::vector<Assignment> technique_assignments;
  for (const auto& text : options.technique_sets) {
    Assignment a = parse_sweep_assignment(text);
    const bool used = std::any_of(techniques.begin(), techniques.end(), [&](const TechniqueDescriptor* t) {
      return (a.scope.empty() || a.scope == t->id) && has_param(*t, a.key);
    });
    if (!used) throw std::invalid_argument("--set " + text + ": no selected technique has a parameter '" + a.key + "'");
    technique_assignments.push_back(a);
  }
  std::vector<Assignment> scene_assignments;
  for (const auto& text : options.scene_sets) scene_assignments.push_back(parse_sweep_assignment(text));

  std::optional<ClockKind> clock;
  if (options.clock != "auto") clock = parse_clock_kind(options.clock);
  const glm::vec3 background = parse_background(options.background);

  std::vector<std::string> cameras;
  for (const auto& text : options.cameras)
    for (const auto& view : expand_camera_spec(text)) cameras.push_back(view);

  std::optional<uint64_t> memory_budget;
  if (!options.memory_budget.empty()) memory_budget = parse_memory_size(options.memory_budget);

  std::vector<bool> scene_rects;
  for (const auto& text : options.scene_rects) scene_rects.push_back(parse_on_off("--scene-rect", text));

  std::vector<RunSpec> runs;
  for (const auto& scene : options.scenes) {
    for (const auto& scene_params : combinations(scene_assignments)) {
      for (const auto& camera : cameras) {
        for (const auto& size : options.sizes) {
          int width = 0, height = 0;
          parse_size(size == "auto" ? options.auto_size : size, width, height);
          for (const TechniqueDescriptor* t : techniques) {
            std::vector<Assignment> own;
            for (const auto& a : technique_assignments)
              if ((a.scope.empty() || a.scope == t->id) && has_param(*t, a.key)) own.push_back(a);
            for (const auto& params : combinations(own)) {
              for (const bool scene_rect : scene_rects) {
                RunSpec spec = run_of(t->id, params, scene, scene_params, width, height);
                spec.camera = camera;
                apply_repetition(options, spec);
                spec.clock = clock;
                spec.background = background;
                spec.scene_rect = scene_rect;
                spec.memory_budget = memory_budget;
                runs.push_back(spec);
              }
            }
          }
        }
      }
    }
  }
  validate_sweep(runs, registry);
  return runs;
}

void validate_sweep(const std::vector<RunSpec>& runs, const TechniqueRegistry& registry) {
  // Each distinct parameter set once: path parameters touch the disk.
  std::set<std::pair<std::string, RawParams>> techniques, scenes;
  for (size_t i = 0; i < runs.size(); ++i) {
    const RunSpec& spec = runs[i];
    try {
      if (techniques.insert({spec.technique, spec.params}).second) {
        const TechniqueDescriptor& technique = registry.get(spec.technique);
        ParamSet(technique.params, spec.params, "technique '" + spec.technique + "'");
      }
      if (scenes.insert({spec.scene, spec.scene_params}).second) canonical_scene_params(spec.scene, spec.scene_params);
    } catch (const std::exception& e) {
      throw std::invalid_argument("run " + std::to_string(i + 1) + " of " + std::to_string(runs.size()) +
                                  " of the sweep: " + e.what() + " (nothing was run)");
    }
  }
}

std::optional<RunKey> resume_key(const RunSpec& spec, const TechniqueRegistry& registry) {
  try {
    const TechniqueDescriptor& technique = registry.get(spec.technique);
    return RunKey{spec.technique,
                  ParamSet(technique.params, spec.params, "technique '" + spec.technique + "'").canonical(),
                  spec.scene,
                  canonical_scene_params(spec.scene, spec.scene_params),
                  spec.camera,
                  spec.width,
                  spec.height,
                  spec.scene_rect};
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::string run_name(const RunSpec& spec, const RunNaming& naming) {
  std::string name = spec.technique;
  for (const auto& [key, value] : spec.params) name += naming.separator + key + naming.assign + value;
  name += naming.scene + spec.scene;
  for (const auto& [key, value] : spec.scene_params) name += naming.separator + key + naming.assign + value;
  name += naming.separator + std::to_string(spec.width) + "x" + std::to_string(spec.height);
  if (spec.camera != "default") name += naming.camera + spec.camera;
  if (!spec.scene_rect) name += naming.scene_rect_off;
  return name;
}

std::string run_label(const RunResult& result) {
  const RunSpec& spec = result.spec;
  // A scene file is named by its file name (a path's directories would make
  // names long); two files of one name in different folders still get
  // distinct image files, from write_new_image's suffix.
  const std::string scene = spec.scene.find_first_of("/.") == std::string::npos
                                ? spec.scene
                                : std::filesystem::path(spec.scene).filename().string();
  RunSpec named = spec;
  named.scene = scene;
  // What ran: the given parameters at their resolved values, and every
  // `auto` the resolution rule turned into a value.
  const auto requested = csv_pairs(result.requested_params);
  for (const auto& [key, value] : csv_pairs(result.technique_params)) {
    const auto asked = std::find_if(requested.begin(), requested.end(), [&](const auto& p) { return p.first == key; });
    if (named.params.count(key) || (asked != requested.end() && asked->second != value)) named.params[key] = value;
  }
  std::string label = run_name(named, {"_", "-", "_", "_camera-", "_scene-rect-off"});
  for (char& c : label)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-' && c != '.') c = '-';
  // File names end at 255 bytes: a long one keeps its start and a hash of the whole.
  if (label.size() > 180) {
    char hash[20];
    std::snprintf(hash, sizeof hash, "_%016llx", static_cast<unsigned long long>(std::hash<std::string>{}(label)));
    label = label.substr(0, 160) + hash;
  }
  return label;
}

}  // namespace oit
