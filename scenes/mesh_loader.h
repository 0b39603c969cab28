#pragma once
// OBJ, OFF, PLY and STL files through OpenMesh's readers.
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "scenes/scene.h"

namespace oit {

// Every connected component gets this opacity (the files carry no usable
// transparency) and a colour from a fixed palette.
inline constexpr float kMeshAlpha = 0.4f;
glm::vec4 mesh_component_color(uint32_t component);

// True for .obj, .off, .ply and .stl in any letter case.
bool is_mesh_file(const std::string& path);

// Loads a mesh file as ONE indexed triangle mesh, lit, under a perspective
// camera framing its bounding sphere from +z:
// - the file's vertices stay shared (one Vertex per file vertex; STL has no
//   indices, and OpenMesh's STL reader merges corners with equal positions);
//   vertices no face uses are dropped;
// - polygons are triangulated as fans around their first corner;
// - each connected component (faces sharing vertices) is one object id and
//   one surface id, numbered in order of first appearance;
// - normals come from the file where it has finite non-zero ones, else they
//   are area-weighted averages of the adjacent faces;
// - zero-area triangles are kept (they rasterise to no fragments and add
//   nothing to normals). OpenMesh itself already drops OBJ faces left with
//   fewer than 3 distinct corners and STL facets whose corners coincide.
// Throws std::invalid_argument naming the file and the problem for anything
// malformed: empty or truncated files, non-finite or unparsable
// coordinates, indices past the vertex count, implausible declared counts,
// files without faces.
Scene load_mesh_scene(const std::string& path);

}  // namespace oit
