#pragma once
// `oitbench adaptive`: every adaptive feature on and off on the same scenes.
// A feature is one of a technique's TechniqueDescriptor::adaptive_switches
// (parameter settings for on and off) or the harness's own scene rectangle
// (RunSpec::scene_rect), so nothing here knows any technique. The two runs
// of a feature alternate in order over the repeats, in one process, so that
// drift of a shared machine hits both; the table gives time and memory
// ratios, the image difference between them and the work the `on` run saved.
#include <string>
#include <vector>

#include "harness/app/commands.h"

namespace oit {

struct AdaptiveOptions {
  // Technique ids or "all"; empty: every technique that declares switches.
  std::vector<std::string> techniques;
  // Features to run (switch names or "scene_rect"); empty: all of them.
  std::vector<std::string> features;
  // Scene specs "ID" or "ID:key=value,key=value"; empty: kPresetScenes.
  std::vector<std::string> scenes;
  std::string size = kDefaultSize;
  int frames = 5;
  int warmup = 1;
  int repeats = 2;  // on/off pairs, the order alternating
  std::string background = "0,0,0";
  std::string csv;  // every run appended when set
};

// Stacked quads with few and many layers, the engine glTF (very uneven
// depth complexity) and a single-object mesh.
extern const std::vector<std::string> kPresetScenes;

// The harness's own feature, offered for every technique.
extern const char* const kSceneRectFeature;

// "ID" or "ID:key=value,key=value" -> scene id and its parameters; throws
// naming the text when an assignment is malformed.
void parse_scene_spec(const std::string& text, std::string& scene, RawParams& params);

int run_adaptive(const CommonOptions& common, const AdaptiveOptions& options);

}  // namespace oit
