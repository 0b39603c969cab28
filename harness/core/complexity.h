#pragma once
#include <cstdint>
#include <vector>

#include "core/scene_gpu.h"

namespace oit {

// Depth complexity of one view: fragments per pixel.
struct DepthComplexity {
  int width = 0, height = 0;
  std::vector<uint32_t> per_pixel;  // bottom-up rows
  uint64_t fragments = 0;
  uint32_t max = 0;
  double mean = 0.0;  // over all pixels
};

// Renders the scene once with a counting shader (no depth test, no culling).
DepthComplexity measure_depth_complexity(const SceneGpu& scene, const glm::mat4& view, const glm::mat4& projection,
                                         int width, int height);

}  // namespace oit
