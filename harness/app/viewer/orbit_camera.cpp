#include "harness/app/viewer/orbit_camera.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace oit {

OrbitCamera::OrbitCamera(const Camera& preset, const BoundingSphere& sphere) : preset_(preset), sphere_(sphere) {
  const glm::mat4 camera_to_world = glm::inverse(preset.view);
  const glm::vec3 eye(camera_to_world[3]);
  orientation_ = glm::normalize(glm::quat_cast(glm::mat3(camera_to_world)));
  const glm::vec3 forward = orientation_ * glm::vec3(0.0f, 0.0f, -1.0f);
  up_ = orientation_ * glm::vec3(0.0f, 1.0f, 0.0f);
  // Presets look at the bounding sphere; taking its centre's depth along
  // the axis keeps the target on the axis even for off-centre views.
  distance_ = std::max(glm::dot(sphere.center - eye, forward), 1e-3f * std::max(sphere.radius, 1.0f));
  target_ = eye + forward * distance_;
}

glm::vec3 OrbitCamera::eye() const { return target_ + orientation_ * glm::vec3(0.0f, 0.0f, distance_); }

void OrbitCamera::orbit(float dx, float dy, float image_height) {
  // Half the image height of drag turns the view by about 90 degrees.
  const float radians_per_pixel = 3.14159265f / std::max(image_height, 1.0f);
  const glm::quat yaw = glm::angleAxis(-dx * radians_per_pixel, up_);
  const glm::quat pitch = glm::angleAxis(-dy * radians_per_pixel, glm::vec3(1.0f, 0.0f, 0.0f));
  orientation_ = glm::normalize(yaw * orientation_ * pitch);
  moved_ = true;
}

void OrbitCamera::pan(float dx, float dy, float image_height) {
  // The target follows the cursor: the view height at the target's depth
  // spans image_height pixels.
  const float view_height = preset_.orthographic ? 2.0f * preset_.ymag * ortho_scale_
                                                 : 2.0f * distance_ * std::tan(preset_.yfov_radians * 0.5f);
  const float scale = view_height / std::max(image_height, 1.0f);
  target_ += orientation_ * glm::vec3(-dx * scale, dy * scale, 0.0f);
  moved_ = true;
}

void OrbitCamera::zoom(float steps) {
  const float factor = std::exp(-0.15f * steps);
  if (preset_.orthographic) ortho_scale_ *= factor;
  // Never through the target: it would flip the view.
  distance_ = std::max(distance_ * factor, 1e-4f * std::max(sphere_.radius, 1e-3f));
  moved_ = true;
}

Camera OrbitCamera::camera() const {
  if (!moved_) return preset_;
  Camera camera = preset_;
  const glm::mat4 camera_to_world = glm::translate(glm::mat4(1.0f), eye()) * glm::mat4_cast(orientation_);
  camera.view = glm::inverse(camera_to_world);
  camera.ymag *= ortho_scale_;
  camera.xmag *= ortho_scale_;
  // Keep the whole scene between the clip planes wherever the eye went:
  // the far plane behind the sphere, the near plane before it (or close to
  // the eye when the eye is inside the sphere).
  const float eye_to_centre = glm::length(eye() - sphere_.center);
  camera.zfar = std::max(preset_.zfar, eye_to_centre + 2.0f * sphere_.radius);
  const float gap = eye_to_centre - sphere_.radius;
  camera.znear = std::min(preset_.znear, gap > 0.0f ? 0.5f * gap : 1e-3f * std::max(sphere_.radius, 1e-3f));
  return camera;
}

}  // namespace oit
