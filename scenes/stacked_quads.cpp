#include "scenes/stacked_quads.h"

#include <algorithm>
#include <numeric>
#include <random>
#include <stdexcept>

namespace oit {
namespace {

// mt19937's raw sequence is fixed by the standard (the distributions are
// not), so scenes are identical on every platform.
float unit_float(std::mt19937& rng) { return float(rng() >> 8) * (1.0f / 16777216.0f); }

glm::vec3 hue_to_rgb(float hue) {
  const glm::vec3 k(0.0f, 2.0f / 3.0f, 1.0f / 3.0f);
  glm::vec3 p = glm::abs(glm::fract(glm::vec3(hue) + k) * 6.0f - 3.0f);
  return glm::clamp(p - 1.0f, 0.0f, 1.0f) * 0.8f + 0.1f;
}

}  // namespace

std::vector<QuadLayer> stacked_quad_layers(const StackedQuadsParams& params) {
  if (params.layers < 1) throw std::invalid_argument("quads: layers must be >= 1");
  if (params.objects < 1) throw std::invalid_argument("quads: objects must be >= 1");
  std::mt19937 rng(params.seed);
  // Depths are a random permutation of evenly spaced slots: random order,
  // but never two layers closer than one slot (1/layers of the depth range),
  // which keeps 16-bit depth keys exact on this scene.
  std::vector<int> slot(static_cast<size_t>(params.layers));
  std::iota(slot.begin(), slot.end(), 0);
  for (size_t i = slot.size() - 1; i > 0; --i) std::swap(slot[i], slot[rng() % (i + 1)]);
  std::vector<QuadLayer> layers;
  for (int i = 0; i < params.layers; ++i) {
    QuadLayer layer;
    layer.eye_distance = 1.0f + float(slot[size_t(i)]);
    layer.color = glm::vec4(hue_to_rgb(unit_float(rng)), params.alpha);
    layer.object_id = rng() % uint32_t(params.objects);
    layers.push_back(layer);
  }
  return layers;
}

Scene make_stacked_quads(const StackedQuadsParams& params) {
  Scene scene;
  scene.name = "quads";
  scene.lit = false;
  const auto layers = stacked_quad_layers(params);
  uint32_t max_object = 0;
  for (size_t i = 0; i < layers.size(); ++i) {
    const QuadLayer& layer = layers[i];
    // Larger than the [-1, 1] view so that every pixel centre is covered.
    append_facing_quad(scene, glm::vec2(0.0f), 1.5f, layer.eye_distance, layer.color, layer.object_id, uint32_t(i),
                       uint32_t(i));
    max_object = std::max(max_object, layer.object_id);
  }
  scene.object_count = max_object + 1;
  scene.camera = orthographic_square_camera(0.5f, float(params.layers) + 1.5f);
  return scene;
}

glm::dvec4 composite_quad_layers(std::vector<QuadLayer> layers, const glm::vec3& background,
                                 const std::function<double(double)>& opacity) {
  std::stable_sort(layers.begin(), layers.end(),
                   [](const QuadLayer& a, const QuadLayer& b) { return a.eye_distance < b.eye_distance; });
  glm::dvec3 accumulated(0.0);
  double transmittance = 1.0;
  for (const QuadLayer& layer : layers) {
    const double alpha = opacity ? opacity(double(layer.color.a)) : double(layer.color.a);
    const double weight = transmittance * alpha;
    accumulated.r += weight * double(layer.color.r);
    accumulated.g += weight * double(layer.color.g);
    accumulated.b += weight * double(layer.color.b);
    transmittance *= 1.0 - alpha;
  }
  return glm::dvec4(accumulated + transmittance * glm::dvec3(background), 1.0 - transmittance);
}

glm::vec4 stacked_quads_closed_form(const StackedQuadsParams& params, const glm::vec3& background) {
  return glm::vec4(composite_quad_layers(stacked_quad_layers(params), background));
}

}  // namespace oit
