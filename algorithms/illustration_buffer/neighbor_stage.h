#pragma once
// The neighbour search (stage "neighbors"): each sorted fragment's links to
// its geodesic neighbours in the 4 adjacent pixels, by carnecky2013's
// continuity heuristic (neighbors.comp, once per fragment) or by shared
// vertex indices (pastyrik2016 Algorithm 3, neighbors_triangle_index.comp,
// once per covered pixel).
#include <cstdint>
#include <map>

#include "algorithms/illustration_buffer/dispatch.h"
#include "algorithms/illustration_buffer/frame_params.h"
#include "algorithms/illustration_buffer/settings.h"
#include "harness/toolkit/technique.h"

namespace oit::illustration_buffer {

class NeighborStage {
 public:
  explicit NeighborStage(const Settings& settings);
  // Before the frame's parameters are uploaded: the scene's bounding-sphere
  // radius of eq. 1 (heuristic), once per scene.
  void prepare(const SceneGpu& scene, FrameParams& params);
  void run(const Frame& frame, uint32_t longest, const Grid& grid);

 private:
  GLuint triangle_search(uint32_t longest);

  const Settings& s_;
  Program heuristic_;
  std::map<uint32_t, Program> triangle_searches_;  // by IB_GROUP
  uint64_t scene_ = 0;  // SceneGpu::serial of the last prepared scene
  float inverse_radius_ = 1.0f;
};

}  // namespace oit::illustration_buffer
