#pragma once
#include <string>

#include "scene.h"

namespace oit {

// Loads a glTF 2.0 file (.gltf or .glb) through tinygltf: every mesh
// instance of the default scene's node tree becomes one object id, with its
// world transform applied. baseColorFactor gives the RGBA of each triangle;
// when every material is KHR_materials_unlit the scene is unlit, so that
// colour is output exactly. The first camera found in the node tree is used,
// otherwise a camera framing the bounding sphere. Throws naming the file and
// the problem for malformed input.
Scene load_gltf_scene(const std::string& path);

}  // namespace oit
