#pragma once
// The part of the image a scene can cover: its bounding box projected with
// the frame's camera, rounded outward. While a technique renders, the
// harness scissors to it, so full-screen passes (clears, resolves, composes)
// skip pixels no fragment can reach. Nothing here knows any technique.
#include <glm/glm.hpp>

#include <cstdint>

namespace oit {

// Axis-aligned box in world space; `empty` when the scene has no vertices.
struct BoundingBox {
  glm::vec3 lo{0.0f}, hi{0.0f};
  bool empty = true;
};

// A window-space rectangle in pixels (origin bottom-left, as glScissor).
struct ScreenRect {
  int x = 0, y = 0, width = 0, height = 0;
  uint64_t pixels() const { return uint64_t(width) * uint64_t(height); }
  bool operator==(const ScreenRect&) const = default;
};

// Conservative rectangle of every pixel whose centre the box's projection
// can cover under `view_projection` on a width x height image:
// - the full image when any corner is not finite, lies behind the near plane
//   (clip z < -w) or behind the eye (clip w <= 0): the box straddles the
//   camera and its projection is unbounded;
// - otherwise the bounds of the eight projected corners, widened by one
//   pixel on every side (rounding of the rasterizer's fixed-point
//   coordinates), clipped to the image; empty (0x0) when the box lies
//   entirely outside the view or the scene has no vertices.
ScreenRect projected_scene_rect(const BoundingBox& box, const glm::mat4& view_projection, int width, int height);

}  // namespace oit
