#pragma once
// Full-screen layers built to stress an OIT technique's numerics: depth gaps
// down to 1e-7 (in NDC under an orthographic camera, or relative eye depth
// under a perspective one with a chosen near/far ratio), exactly coplanar
// layers, alpha at the extremes, and degenerate extras (zero-area triangles,
// non-finite vertices, an empty scene). Every pixel sees the same stack, so
// the exact image is known in closed form (double precision, exact depths).
#include <glm/glm.hpp>

#include <string>

#include "scenes/scene.h"

namespace oit {

struct StressLayersParams {
  int layers = 8;
  double gap = 1e-3;            // between consecutive layers; 0 = coplanar
  std::string space = "ndc";    // "ndc" (orthographic) or "eye" (perspective, gap relative to depth)
  double near_far_ratio = 100;  // perspective only: far / near
  float alpha = 0.5f;
  std::string alpha_mode = "constant";  // "constant" or "mixed" (cycles 1, alpha, 1e-4, 0.5)
  std::string extra = "none";           // "none", "zero_area", "nan_vertex", "inf_vertex", "empty"
  uint32_t seed = 1;                    // submission order of the layers (shuffled)
};

Scene make_stress_layers(const StressLayersParams& params);
// The exact composite (depth order by the double-precision eye distance,
// ties by submission-independent layer index), rounded to float.
glm::vec4 stress_layers_closed_form(const StressLayersParams& params, const glm::vec3& background);

}  // namespace oit
