#pragma once
// Named scenes with parameter schemas, and file loading by extension.
#include <functional>
#include <string>
#include <vector>

#include "base/params.h"
#include "scenes/scene.h"
#include "scenes/stress_layers.h"

namespace oit {

struct SceneDescriptor {
  std::string id;
  std::string description;
  ParamSchema params;
  std::function<Scene(const ParamSet&)> make;
};

const std::vector<SceneDescriptor>& scene_library();

// `spec` is a library id ("quads", "model") or a file path: .gltf/.glb
// (tinygltf) or .obj/.off/.ply/.stl (OpenMesh), extensions in any letter
// case. Scene parameters apply to library scenes only; giving any to a file
// is an error.
Scene load_scene(const std::string& spec, const RawParams& params);

// The canonical parameters load_scene gives the scene (`Scene::params`:
// defaults filled in; "" for a file) without building or reading anything;
// throws like load_scene on an invalid value, an unknown scene id, or
// parameters given to a file (a missing file is load_scene's to find).
std::string canonical_scene_params(const std::string& spec, const RawParams& params);

// The typed parameters of the `stress_layers` scene (for its closed form).
StressLayersParams stress_layers_params(const ParamSet& values);

}  // namespace oit
