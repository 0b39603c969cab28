#include "harness/toolkit/scene_rect.h"

#include <algorithm>
#include <cmath>

namespace oit {

ScreenRect projected_scene_rect(const BoundingBox& box, const glm::mat4& view_projection, int width, int height) {
  const ScreenRect full{0, 0, width, height};
  if (box.empty) return {};
  // Double precision: the outward rounding below must not be eaten by
  // float error on far-away boxes.
  const glm::dmat4 m(view_projection);
  double lo_x = INFINITY, lo_y = INFINITY, hi_x = -INFINITY, hi_y = -INFINITY;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec4 p((corner & 1) ? box.hi.x : box.lo.x, (corner & 2) ? box.hi.y : box.lo.y,
                       (corner & 4) ? box.hi.z : box.lo.z, 1.0);
    const glm::dvec4 clip = m * p;
    if (!std::isfinite(clip.x) || !std::isfinite(clip.y) || !std::isfinite(clip.z) || !std::isfinite(clip.w))
      return full;
    if (clip.w <= 0.0 || clip.z < -clip.w) return full;
    const double x = (clip.x / clip.w * 0.5 + 0.5) * width, y = (clip.y / clip.w * 0.5 + 0.5) * height;
    lo_x = std::min(lo_x, x);
    lo_y = std::min(lo_y, y);
    hi_x = std::max(hi_x, x);
    hi_y = std::max(hi_y, y);
  }
  // Clamp in double before converting: a corner close to the eye plane
  // projects beyond int range.
  auto clamp_to = [](double v, int limit) { return int(std::clamp(v, 0.0, double(limit))); };
  const int x0 = clamp_to(std::floor(lo_x) - 1.0, width), x1 = clamp_to(std::ceil(hi_x) + 1.0, width);
  const int y0 = clamp_to(std::floor(lo_y) - 1.0, height), y1 = clamp_to(std::ceil(hi_y) + 1.0, height);
  if (x1 <= x0 || y1 <= y0) return {};
  return {x0, y0, x1 - x0, y1 - y0};
}

}  // namespace oit
