#pragma once
// Structural checks of OBJ/OFF/PLY/STL bytes BEFORE OpenMesh parses them.
// OpenMesh's readers trust declared counts (a face "4000000000 0 1 2" makes
// them loop four billion times; an OFF header of 2e9 vertices reserves 24 GB),
// silently skip vertices they cannot parse ("v nan 0 0" shifts every later
// index), and feed non-finite positions into ordered maps. Each check walks
// the file the way the OpenMesh reader will, with every count bounded by the
// bytes actually present, so that any file either passes (and OpenMesh reads
// it safely) or is rejected with the file name, the place and the problem.
#include <cstdint>
#include <string>
#include <string_view>

namespace oit {

struct MeshFileFacts {
  std::string format;       // "obj", "off", "ply" or "stl"
  uint64_t vertices = 0;    // vertex records in the file (STL: 3 per facet, before OpenMesh merges them)
  uint64_t faces = 0;       // polygons (STL: facets)
  bool binary = false;
};

// `format` is the lower-case extension without the dot. Throws
// std::invalid_argument("<path>: <problem>") for anything the loader must not
// hand to OpenMesh.
MeshFileFacts check_mesh_file(const std::string& path, const std::string& format, std::string_view bytes);

}  // namespace oit
