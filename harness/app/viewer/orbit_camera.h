#pragma once
// The viewer's interactive camera: orbit around a target point, pan it,
// zoom towards it. It starts from one of the harness's camera presets
// (scenes/cameras.h) and reproduces that preset's view matrix bit for bit
// until the user moves it, so a viewer frame that was not touched is the
// frame `oitbench render --camera ...` draws.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scenes/scene.h"

namespace oit {

class OrbitCamera {
 public:
  OrbitCamera() = default;
  // `preset` is the camera of a preset, `sphere` the scene's bounds: the
  // orbit target is the point on the view axis nearest the sphere's centre.
  OrbitCamera(const Camera& preset, const BoundingSphere& sphere);

  // Drags in pixels of an image `image_height` pixels tall.
  void orbit(float dx, float dy, float image_height);
  void pan(float dx, float dy, float image_height);
  // steps > 0 moves closer (mouse wheel notches).
  void zoom(float steps);
  void reset() { *this = OrbitCamera(preset_, sphere_); }

  bool moved() const { return moved_; }
  Camera camera() const;  // the preset's own camera while not moved
  glm::vec3 eye() const;
  float distance() const { return distance_; }

 private:
  Camera preset_;
  BoundingSphere sphere_;
  glm::vec3 target_{0.0f};
  glm::quat orientation_{1.0f, 0.0f, 0.0f, 0.0f};  // camera to world
  glm::vec3 up_{0.0f, 1.0f, 0.0f};  // the preset's up: orbiting turns about it (turntable)
  float distance_ = 1.0f;
  float ortho_scale_ = 1.0f;  // orthographic presets zoom by scaling the view volume
  bool moved_ = false;
};

}  // namespace oit
