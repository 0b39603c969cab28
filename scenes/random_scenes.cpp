#include "scenes/random_scenes.h"

#include <algorithm>
#include <numeric>
#include <random>
#include <stdexcept>

#include "scenes/parametric.h"

namespace oit {
namespace {

// mt19937's raw sequence is fixed by the standard (the distributions are
// not), so the scenes are identical on every platform.
float unit_float(std::mt19937& rng) { return float(rng() >> 8) * (1.0f / 16777216.0f); }

}  // namespace

Scene make_random_quads(const RandomQuadsParams& params) {
  if (params.count < 1) throw std::invalid_argument("random_quads: count must be >= 1");
  if (!(params.size > 0.0f)) throw std::invalid_argument("random_quads: size must be > 0");
  if (params.order != "random" && params.order != "front_to_back" && params.order != "back_to_front")
    throw std::invalid_argument("random_quads: order '" + params.order + "' is not random, front_to_back or back_to_front");
  std::mt19937 rng(params.seed);
  // Distinct depth slots, as in the stacked quads: no ties, 16-bit safe.
  std::vector<int> slot(size_t(params.count));
  std::iota(slot.begin(), slot.end(), 0);
  for (size_t i = slot.size() - 1; i > 0; --i) std::swap(slot[i], slot[rng() % (i + 1)]);
  struct Quad {
    glm::vec2 center;
    float distance;
    glm::vec4 color;
  };
  std::vector<Quad> quads;
  const float half = params.size;  // the view spans 2 units: a side of size * 2 units has half-side size
  for (int i = 0; i < params.count; ++i) {
    Quad q;
    q.center = glm::vec2(unit_float(rng), unit_float(rng)) * 2.0f - 1.0f;
    q.distance = 1.0f + float(slot[size_t(i)]);
    q.color = glm::vec4(0.15f + 0.8f * unit_float(rng), 0.15f + 0.8f * unit_float(rng), 0.15f + 0.8f * unit_float(rng),
                        params.alpha);
    quads.push_back(q);
  }
  if (params.order == "front_to_back")
    std::sort(quads.begin(), quads.end(), [](const Quad& a, const Quad& b) { return a.distance < b.distance; });
  if (params.order == "back_to_front")
    std::sort(quads.begin(), quads.end(), [](const Quad& a, const Quad& b) { return a.distance > b.distance; });
  Scene scene;
  scene.name = "random_quads";
  scene.lit = false;
  for (size_t i = 0; i < quads.size(); ++i)
    append_facing_quad(scene, quads[i].center, half, quads[i].distance, quads[i].color, uint32_t(i), uint32_t(i),
                       uint32_t(i));
  scene.object_count = uint32_t(quads.size());
  scene.camera = orthographic_square_camera(0.5f, float(params.count) + 1.5f);
  return scene;
}

Scene make_particles(const ParticlesParams& params) {
  if (params.per_axis < 1) throw std::invalid_argument("particles: per_axis must be >= 1");
  std::mt19937 rng(params.seed);
  Scene scene;
  scene.name = "particles";
  const float spacing = 2.0f / float(params.per_axis);
  const float radius = 0.4f * spacing;
  uint32_t id = 0;
  for (int z = 0; z < params.per_axis; ++z) {
    for (int y = 0; y < params.per_axis; ++y) {
      for (int x = 0; x < params.per_axis; ++x) {
        const glm::vec3 jitter = (glm::vec3(unit_float(rng), unit_float(rng), unit_float(rng)) - 0.5f) * 0.3f * spacing;
        const glm::vec3 center = (glm::vec3(x, y, z) + 0.5f) * spacing - 1.0f + jitter;
        const glm::vec4 color(0.2f + 0.7f * unit_float(rng), 0.2f + 0.7f * unit_float(rng),
                              0.2f + 0.7f * unit_float(rng), params.alpha);
        append_uv_sphere(scene, center, radius, params.slices, params.stacks, color, id, id);
        ++id;
      }
    }
  }
  scene.object_count = id;
  scene.analytic_curvature = true;
  scene.camera = frame_bounding_sphere(scene.bounds());
  return scene;
}

}  // namespace oit
