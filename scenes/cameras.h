#pragma once
// Viewpoints other than a scene's own camera, named by short text specs so
// that a run, a CSV row and a cached reference can say which one they used:
//   default            the scene's camera
//   random:N:SEED      a set of N seeded random viewpoints on a sphere around
//                      the scene's bounding sphere (the bounding sphere fills
//                      the image); a set expands to one run per viewpoint,
//                      each labelled random:N:SEED@I
//   random:N:SEED@I    viewpoint I (0-based) of that set
//   max_list[:N:SEED]  among random:N:SEED (default N=16, SEED=1), the
//                      viewpoint whose longest per-pixel fragment list is
//                      longest (pastyrik2016 section 4: each model "in one
//                      position where the length of linked list is maximum");
//                      needs the GPU, see choose_max_list_camera().
// Viewpoint I depends only on SEED and I, not on N, so random:4:7@2 and
// random:9:7@2 are the same view. Directions come from std::mt19937, whose
// output the C++ standard fixes, so views reproduce across machines.
#include <cstdint>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace oit {

struct CameraSpec {
  enum class Kind { scene_default, random_set, random_view, max_list };
  Kind kind = Kind::scene_default;
  uint32_t count = 1;  // random_set, random_view, max_list: viewpoints in the set
  uint32_t seed = 1;
  uint32_t index = 0;  // random_view
  std::string text() const;  // canonical spec
};

// Throws std::invalid_argument naming the text for anything else.
CameraSpec parse_camera_spec(const std::string& text);

// One spec per run: a random set becomes its viewpoints, the rest stay one.
std::vector<std::string> expand_camera_spec(const std::string& text);

// Viewpoint `index` of the seeded set around `sphere`.
Camera random_viewpoint(const BoundingSphere& sphere, uint32_t seed, uint32_t index);

// The camera of a spec that needs no rendering (default and random views);
// throws for sets and max_list.
Camera camera_for_spec(const Scene& scene, const CameraSpec& spec);

}  // namespace oit
