#pragma once
// The synthetic benchmark of murray2016 section 6: `layers` full-screen quads,
// each at a random depth and with a random object id in [0, objects), so every
// pixel has exactly `layers` fragments. Because every pixel sees the same
// stack, the exact composite is known in closed form.
#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <vector>

#include "scenes/scene.h"

namespace oit {

struct StackedQuadsParams {
  int layers = 32;
  int objects = 32;
  uint32_t seed = 1;
  float alpha = 0.3f;
};

struct QuadLayer {
  float eye_distance;  // distance from the camera along -z
  glm::vec4 color;     // straight RGBA
  uint32_t object_id;
};

// Layers in submission order (layer i is quad i: triangles 2i and 2i+1).
std::vector<QuadLayer> stacked_quad_layers(const StackedQuadsParams& params);
Scene make_stacked_quads(const StackedQuadsParams& params);

// Exact composite of `layers` over `background`, sorted by eye distance
// (ties keep their order) and composited front to back in double precision,
// in the same operation order as the reference technique (acc += T*a*c;
// T *= 1-a; out = acc + T*bg, alpha = 1-T). `opacity` maps each layer's alpha
// to the one composited (a technique's own alpha model); default: as given.
glm::dvec4 composite_quad_layers(std::vector<QuadLayer> layers, const glm::vec3& background,
                                 const std::function<double(double)>& opacity = {});
// composite_quad_layers() of the stack, rounded to float.
glm::vec4 stacked_quads_closed_form(const StackedQuadsParams& params, const glm::vec3& background);

}  // namespace oit
