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

#include "base/suggest.h"
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
  std::string text;   // as given, for messages
  std::string scope;  // technique or scene id, or "" for every selected one that has the key
  std::string key;
  std::vector<std::string> values;
};

// "key=v1,v2" or "scope.key=v1,v2"; `lists`: split the values at ','
// (sweeps), else one value as given (the commands that run once).
Assignment parse_scoped_assignment(const std::string& option, const std::string& text, bool lists) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw std::invalid_argument(option + " '" + text + "' is not of the form key=value");
  Assignment a;
  a.text = text;
  a.key = text.substr(0, eq);
  if (const auto dot = a.key.find('.'); dot != std::string::npos) {
    a.scope = a.key.substr(0, dot);
    a.key = a.key.substr(dot + 1);
  }
  if (a.key.empty())
    throw std::invalid_argument(option + " '" + text + "' is not of the form key=value or id.key=value");
  a.values = lists ? split(text.substr(eq + 1), ',') : std::vector<std::string>{text.substr(eq + 1)};
  return a;
}

// A technique or scene a command selected, with its parameters' names.
struct ParamOwner {
  std::string id;
  std::vector<std::string> keys;
  bool has(const std::string& key) const { return std::find(keys.begin(), keys.end(), key) != keys.end(); }
};

ParamOwner technique_owner(const TechniqueDescriptor& t) {
  ParamOwner owner{t.id, {}};
  for (const ParamSpec& spec : t.params) owner.keys.push_back(spec.name);
  return owner;
}

// A library scene's parameters; a scene file (or an id validate_sweep will
// name as unknown) has none.
ParamOwner scene_owner(const std::string& scene) {
  ParamOwner owner{scene, {}};
  for (const SceneDescriptor& descriptor : scene_library())
    if (descriptor.id == scene)
      for (const ParamSpec& spec : descriptor.params) owner.keys.push_back(spec.name);
  return owner;
}

std::string comma_list(const std::vector<std::string>& values) {
  std::string text;
  for (const auto& value : values) text += (text.empty() ? "" : ",") + value;
  return text;
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

// How a command names its options' owners in messages: `option` is --set
// or --scene-set, `kind` technique or scene, `select` the option that
// selects one (-t, -s), `lists` whether values are lists (sweeps).
struct AssignmentOption {
  std::string option, kind, select;
  bool lists;
};

// The assignments of `texts`, each checked against the selected owners: a
// scope that names no known id or no selected one, a key no owner in scope
// has, and one key given twice for one scope are errors naming the text.
std::vector<Assignment> checked_assignments(const AssignmentOption& how, const std::vector<std::string>& texts,
                                            const std::vector<ParamOwner>& selected,
                                            const std::vector<std::string>& known_ids) {
  std::vector<std::string> selected_ids;
  for (const ParamOwner& owner : selected) selected_ids.push_back(owner.id);
  std::vector<Assignment> assignments;
  for (const auto& text : texts) {
    Assignment a = parse_scoped_assignment(how.option, text, how.lists);
    const std::string given = how.option + " " + text + ": ";
    std::vector<std::string> keys;  // every key in scope, for the suggestion
    if (!a.scope.empty()) {
      const auto owner = std::find_if(selected.begin(), selected.end(), [&](const ParamOwner& o) { return o.id == a.scope; });
      if (owner == selected.end()) {
        if (std::find(known_ids.begin(), known_ids.end(), a.scope) == known_ids.end())
          throw std::invalid_argument(given + "there is no " + how.kind + " '" + a.scope + "'" +
                                      did_you_mean(a.scope, known_ids));
        throw std::invalid_argument(given + a.scope + " is not among the selected " + how.kind + "s (" +
                                    joined(selected_ids) + "); add " + how.select + " " + a.scope +
                                    " or leave this " + how.option + " out");
      }
      keys = owner->keys;
    } else {
      for (const ParamOwner& owner : selected) keys.insert(keys.end(), owner.keys.begin(), owner.keys.end());
    }
    if (std::find(keys.begin(), keys.end(), a.key) == keys.end()) {
      const std::string owner = a.scope.empty() && selected.size() == 1 ? selected.front().id : a.scope;
      throw std::invalid_argument(given + (owner.empty() ? "no selected " + how.kind + " has a"
                                                         : how.kind + " '" + owner + "' has no") +
                                  " parameter '" + a.key + "'" + did_you_mean(a.key, keys));
    }
    for (const Assignment& earlier : assignments) {
      if (earlier.scope != a.scope || earlier.key != a.key) continue;
      const std::string name = (a.scope.empty() ? "" : a.scope + ".") + a.key;
      std::vector<std::string> values = earlier.values;
      values.insert(values.end(), a.values.begin(), a.values.end());
      throw std::invalid_argument(how.option + " " + name + " is given twice (" + earlier.text + ", " + text + "); " +
                                  (how.lists ? "give its values as one list: " + how.option + " " + name + "=" + comma_list(values)
                                             : "give it once"));
    }
    assignments.push_back(a);
  }
  return assignments;
}

// The assignments that apply to `owner`: those scoped to it, and the
// unscoped ones of keys it has that no scoped one sets for it (the scoped
// one is the more specific).
std::vector<Assignment> assignments_of(const std::vector<Assignment>& assignments, const ParamOwner& owner) {
  std::vector<Assignment> own;
  for (const Assignment& a : assignments) {
    if (!a.scope.empty()) {
      if (a.scope == owner.id) own.push_back(a);
      continue;
    }
    const bool scoped_too = std::any_of(assignments.begin(), assignments.end(), [&](const Assignment& b) {
      return b.scope == owner.id && b.key == a.key;
    });
    if (owner.has(a.key) && !scoped_too) own.push_back(a);
  }
  return own;
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

std::vector<std::string> scene_ids() {
  std::vector<std::string> ids;
  for (const SceneDescriptor& descriptor : scene_library()) ids.push_back(descriptor.id);
  return ids;
}

const AssignmentOption kSweepSets{"--set", "technique", "-t", true};
const AssignmentOption kSweepSceneSets{"--scene-set", "scene", "-s", true};

}  // namespace

void apply_repetition(const SweepOptions& options, RunSpec& spec) {
  Repetition& repetition = spec;
  repetition = options.repetition;
  if (repetition.warmup_ms < 0.0) repetition.warmup_ms = options.auto_warmup_ms;
  if (options.exact_frames > 0) {
    repetition.frames = options.exact_frames;
    repetition.precision = 0.0;
    repetition.max_frames = 0;
    repetition.max_seconds = 0.0;
    return;
  }
  repetition.max_frames = std::max(repetition.max_frames, repetition.frames);
}

std::string size_for(const std::string& text, const DeviceProfile& device) {
  return text == "auto" ? device.default_size : text;
}

void parse_size(const std::string& given, int& width, int& height) {
  // Before the device is known (validation), auto stands for the smallest default.
  const std::string text = given == "auto" ? "256x256" : given;
  const auto x = text.find_first_of("xX");
  try {
    if (x == std::string::npos) throw std::invalid_argument("");
    size_t used_w = 0, used_h = 0;
    width = std::stoi(text.substr(0, x), &used_w);
    height = std::stoi(text.substr(x + 1), &used_h);
    if (used_w != x || used_h != text.size() - x - 1) throw std::invalid_argument("");
  } catch (const std::out_of_range&) {
    throw std::invalid_argument("size '" + text + "' is outside 1x1 .. 16384x16384");
  } catch (const std::exception&) {
    // A lone number is the common slip: suggest the square.
    const bool number = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
    throw std::invalid_argument("size '" + text + "' is not of the form WIDTHxHEIGHT" +
                                (number ? "; did you mean " + text + "x" + text + "?" : ""));
  }
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw std::invalid_argument("size '" + text + "' is outside 1x1 .. 16384x16384");
}

glm::vec3 parse_background(const std::string& text) {
  const auto parts = split(text, ',');
  if (parts.size() != 3) throw std::invalid_argument("--background '" + text + "' must be r,g,b");
  glm::vec3 color;
  for (int i = 0; i < 3; ++i) {
    const std::string& part = parts[size_t(i)];
    const std::string given = "--background '" + text + "': '" + part + "' ";
    try {
      size_t used = 0;
      color[i] = std::stof(part, &used);
      if (used != part.size() || !std::isfinite(color[i])) throw std::invalid_argument("");
    } catch (const std::out_of_range&) {
      throw std::invalid_argument(given + "is out of range");
    } catch (const std::exception&) {
      // nan or inf would turn every error metric into nonsense.
      throw std::invalid_argument(given + "is not a finite number");
    }
    // Linear light has no negative amounts; compose.glsl would subtract.
    if (color[i] < 0.0f) throw std::invalid_argument(given + "is negative: colours are linear, each channel >= 0");
  }
  return color;
}

bool parse_on_off(const std::string& option, const std::string& text) {
  if (text == "on") return true;
  if (text == "off") return false;
  throw std::invalid_argument(option + " '" + text + "' must be on or off");
}

std::vector<const TechniqueDescriptor*> selected_techniques(const std::vector<std::string>& ids,
                                                            const TechniqueRegistry& registry) {
  std::vector<const TechniqueDescriptor*> techniques;
  auto add = [&](const TechniqueDescriptor& t) {
    if (std::find(techniques.begin(), techniques.end(), &t) == techniques.end()) techniques.push_back(&t);
  };
  for (const auto& id : ids) {
    if (id == "all") {
      for (const auto& t : registry.all()) add(t);
    } else {
      add(registry.get(id));
    }
  }
  return techniques;
}

std::vector<RunSpec> expand_sweep(const SweepOptions& options, const TechniqueRegistry& registry) {
  const std::vector<const TechniqueDescriptor*> techniques = selected_techniques(options.techniques, registry);
  std::vector<ParamOwner> technique_owners, scene_owners;
  for (const TechniqueDescriptor* t : techniques) technique_owners.push_back(technique_owner(*t));
  for (const auto& scene : options.scenes) scene_owners.push_back(scene_owner(scene));
  const std::vector<Assignment> technique_assignments =
      checked_assignments(kSweepSets, options.technique_sets, technique_owners, registry.ids());
  const std::vector<Assignment> scene_assignments =
      checked_assignments(kSweepSceneSets, options.scene_sets, scene_owners, scene_ids());

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
  for (const ParamOwner& scene : scene_owners) {
    for (const auto& scene_params : combinations(assignments_of(scene_assignments, scene))) {
      for (const auto& camera : cameras) {
        for (const auto& size : options.sizes) {
          int width = 0, height = 0;
          parse_size(size == "auto" ? options.auto_size : size, width, height);
          for (const ParamOwner& technique : technique_owners) {
            for (const auto& params : combinations(assignments_of(technique_assignments, technique))) {
              for (const bool scene_rect : scene_rects) {
                RunSpec spec = run_of(technique.id, params, scene.id, scene_params, width, height);
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

std::vector<RawParams> one_value_technique_params(const std::vector<std::string>& sets,
                                                  const std::vector<const TechniqueDescriptor*>& techniques,
                                                  const TechniqueRegistry& registry) {
  std::vector<ParamOwner> owners;
  for (const TechniqueDescriptor* t : techniques) owners.push_back(technique_owner(*t));
  const std::vector<Assignment> assignments =
      checked_assignments({"--set", "technique", "-t", false}, sets, owners, registry.ids());
  std::vector<RawParams> params;
  for (const ParamOwner& owner : owners) params.push_back(combinations(assignments_of(assignments, owner)).front());
  return params;
}

RawParams one_value_scene_params(const std::vector<std::string>& scene_sets, const std::string& scene) {
  canonical_scene_params(scene, {});  // an unknown scene is named before its parameters
  const std::vector<ParamOwner> owners{scene_owner(scene)};
  const std::vector<Assignment> assignments =
      checked_assignments({"--scene-set", "scene", "-s", false}, scene_sets, owners, scene_ids());
  return combinations(assignments_of(assignments, owners.front())).front();
}

void validate_baseline(const std::string& baseline, const std::vector<std::string>& techniques,
                       const TechniqueRegistry& registry) {
  const std::vector<std::string> ids = registry.ids();
  if (std::find(ids.begin(), ids.end(), baseline) == ids.end()) {
    // "linked_list:sort=insertion": the ratios divide by a technique, whatever its parameters.
    const std::string id = baseline.substr(0, baseline.find_first_of(":. "));
    if (id != baseline && std::find(ids.begin(), ids.end(), id) != ids.end())
      throw std::invalid_argument("--baseline '" + baseline + "' is not a technique id; did you mean " + id +
                                  "? (the ratios divide by a technique's runs, whatever their parameters)");
    throw std::invalid_argument("--baseline '" + baseline + "' is not a technique id" + did_you_mean(baseline, ids));
  }
  std::vector<std::string> selected;
  for (const TechniqueDescriptor* t : selected_techniques(techniques, registry)) selected.push_back(t->id);
  if (std::find(selected.begin(), selected.end(), baseline) == selected.end())
    throw std::invalid_argument("--baseline " + baseline + " is not among the selected techniques (" +
                                joined(selected) + "); add -t " + baseline + " or choose one of them");
}

std::string clock_warning(const std::string& clock, const DeviceProfile& device) {
  if (!device.software || (clock != "gl" && clock != "both")) return "";
  return "warning: --clock " + clock + " on " + device.renderer +
         ", a software device, whose GL timer queries misreport single passes (REFERENCE.md, Timing): "
         "use --clock wall, or --clock both to see how far gl is off";
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
