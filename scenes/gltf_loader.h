#pragma once
#include <string>

#include "scenes/scene.h"

namespace oit {

// Loads a glTF 2.0 file (.gltf or .glb) through tinygltf: every mesh
// instance of the default scene's node tree (a mesh used by several nodes
// gives several instances) becomes one object id and one surface id, with
// its world transform applied. Indices may be unsigned byte, short or int;
// missing normals are area-weighted face normals. baseColorFactor gives the
// RGBA of each triangle (textures are ignored, images not even decoded);
// alphaMode OPAQUE sets alpha 1, MASK sets 1 or 0 by alphaCutoff, BLEND keeps
// it. When every material is KHR_materials_unlit the scene is unlit, so that
// colour is output exactly (one lit material makes the whole scene lit). The
// first camera found in the node tree is used (its aspectRatio is ignored:
// the image's aspect rules), otherwise a camera framing the bounding sphere.
// Zero-area triangles are kept: they produce no fragments.
// Throws std::invalid_argument naming the file and the problem for malformed
// input: the file or a buffer it names not a regular file (a FIFO, device or
// directory), truncated files, accessors reading past their buffers, index or
// node references out of range, nodes reached twice (cycles), non-finite
// positions, non-triangle primitives, no triangles, declared sizes that
// would need more than 2^25 vertices or 2^26 triangles, and node transforms
// that leave a scene float rendering cannot draw (naming the node): vertices
// beyond 1e16 from the origin, a scene less than 1e-16 across, or one so far
// from the origin that fewer than 128 float steps span it.
Scene load_gltf_scene(const std::string& path);

}  // namespace oit
