#include "scenes/stress_layers.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>

namespace oit {
namespace {

struct Layer {
  double distance;  // eye distance, exact
  glm::vec4 color;
  uint32_t index;   // stable id (tie-break)
};

constexpr float kFovY = 0.8f;

double orthographic_near(const StressLayersParams&) { return 1.0; }
double orthographic_far(const StressLayersParams&) { return 3.0; }

std::vector<Layer> stress_layers(const StressLayersParams& p) {
  if (p.layers < 1) throw std::invalid_argument("stress_layers: layers must be >= 1");
  if (!(p.gap >= 0.0)) throw std::invalid_argument("stress_layers: gap must be >= 0");
  if (p.space != "ndc" && p.space != "eye")
    throw std::invalid_argument("stress_layers: space '" + p.space + "' is not ndc or eye");
  if (p.alpha_mode != "constant" && p.alpha_mode != "mixed")
    throw std::invalid_argument("stress_layers: alpha_mode '" + p.alpha_mode + "' is not constant or mixed");
  double first = 0.0, step = 0.0;
  if (p.space == "ndc") {
    // Orthographic depth maps [near, far] linearly onto NDC [-1, 1].
    const double n = orthographic_near(p), f = orthographic_far(p);
    step = p.gap * (f - n) / 2.0;
    first = (n + f) / 2.0 - step * double(p.layers - 1) / 2.0;
  } else {
    // Perspective: layers around the geometric middle of [near, far].
    const double middle = std::sqrt(p.near_far_ratio);  // near = 1
    step = p.gap * middle;
    first = middle - step * double(p.layers - 1) / 2.0;
  }
  const float mixed[] = {1.0f, p.alpha, 1e-4f, 0.5f};
  std::vector<Layer> layers;
  for (int i = 0; i < p.layers; ++i) {
    const float hue = float(i) / float(p.layers);
    const glm::vec3 rgb = 0.15f + 0.8f * glm::vec3(std::fabs(std::sin(6.2831853f * hue)),
                                                    std::fabs(std::sin(6.2831853f * (hue + 0.33f))),
                                                    std::fabs(std::sin(6.2831853f * (hue + 0.67f))));
    const float alpha = p.alpha_mode == "mixed" ? mixed[i % 4] : p.alpha;
    layers.push_back({first + step * double(i), glm::vec4(rgb, alpha), uint32_t(i)});
  }
  return layers;
}

}  // namespace

Scene make_stress_layers(const StressLayersParams& p) {
  std::vector<Layer> layers = stress_layers(p);
  if (p.extra != "none" && p.extra != "zero_area" && p.extra != "nan_vertex" && p.extra != "inf_vertex" &&
      p.extra != "empty")
    throw std::invalid_argument("stress_layers: extra '" + p.extra + "' is not none, zero_area, nan_vertex, inf_vertex or empty");
  Scene scene;
  scene.name = "stress_layers";
  scene.lit = false;
  // Submission order is shuffled; the stable triangle ids follow the layer index.
  std::vector<size_t> order(layers.size());
  std::iota(order.begin(), order.end(), 0);
  std::mt19937 rng(p.seed);
  for (size_t i = order.size() - 1; i > 0; --i) std::swap(order[i], order[rng() % (i + 1)]);
  const double far = p.space == "ndc" ? orthographic_far(p) : p.near_far_ratio;
  if (p.extra != "empty") {
    for (size_t k : order) {
      const Layer& layer = layers[k];
      // Large enough to cover the view at this distance (perspective) or the ortho box.
      const float half = p.space == "ndc" ? 1.5f : float(layer.distance * std::tan(kFovY * 0.5) * 3.0);
      append_facing_quad(scene, glm::vec2(0.0f), half, float(layer.distance), layer.color, layer.index, layer.index,
                         layer.index);
    }
  }
  if (p.extra == "zero_area" || p.extra == "nan_vertex" || p.extra == "inf_vertex") {
    // A triangle whose three indices coincide (zero area) or whose vertex is not finite.
    const auto base = uint32_t(scene.vertices.size());
    Vertex v;
    v.position = glm::vec3(0.0f, 0.0f, -float(layers.front().distance));
    if (p.extra == "nan_vertex") v.position.x = std::numeric_limits<float>::quiet_NaN();
    if (p.extra == "inf_vertex") v.position.y = std::numeric_limits<float>::infinity();
    scene.vertices.push_back(v);
    scene.indices.insert(scene.indices.end(), {base, base, base});
    scene.triangle_ids.push_back(uint32_t(2 * layers.size()));
  }
  scene.object_count = uint32_t(layers.size());
  if (p.space == "ndc") {
    scene.camera = orthographic_square_camera(float(orthographic_near(p)), float(far));
  } else {
    scene.camera.yfov_radians = kFovY;
    scene.camera.znear = 1.0f;
    scene.camera.zfar = float(far);
  }
  return scene;
}

glm::vec4 stress_layers_closed_form(const StressLayersParams& p, const glm::vec3& background) {
  std::vector<Layer> layers = p.extra == "empty" ? std::vector<Layer>{} : stress_layers(p);
  std::stable_sort(layers.begin(), layers.end(), [](const Layer& a, const Layer& b) {
    return a.distance != b.distance ? a.distance < b.distance : a.index < b.index;
  });
  glm::dvec3 accumulated(0.0);
  double transmittance = 1.0;
  for (const Layer& layer : layers) {
    const double weight = transmittance * double(layer.color.a);
    accumulated += weight * glm::dvec3(layer.color);
    transmittance *= 1.0 - double(layer.color.a);
  }
  const glm::dvec3 result = accumulated + transmittance * glm::dvec3(background);
  return glm::vec4(glm::vec3(result), float(1.0 - transmittance));
}

}  // namespace oit
