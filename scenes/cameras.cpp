#include "scenes/cameras.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace oit {
namespace {

constexpr uint32_t kMaxViewpoints = 4096;
constexpr uint32_t kDefaultMaxListCount = 16;

uint32_t number(const std::string& text, const std::string& part, const char* what, uint32_t lowest, uint32_t highest) {
  try {
    size_t used = 0;
    const unsigned long long value = std::stoull(part, &used);
    if (used != part.size() || part.empty() || part[0] == '-' || part[0] == '+' || value < lowest || value > highest)
      throw std::invalid_argument("");
    return uint32_t(value);
  } catch (const std::exception&) {
    throw std::invalid_argument("camera '" + text + "': " + what + " '" + part + "' is not a whole number in " +
                                std::to_string(lowest) + " .. " + std::to_string(highest));
  }
}

// Uniform in [0, 1) from the top 24 bits of one mt19937 draw (the standard
// distributions are implementation-defined; this is not).
double unit(std::mt19937& rng) { return double(rng() >> 8) * (1.0 / 16777216.0); }

}  // namespace

std::string CameraSpec::text() const {
  const std::string set = std::to_string(count) + ":" + std::to_string(seed);
  switch (kind) {
    case Kind::scene_default: return "default";
    case Kind::random_set: return "random:" + set;
    case Kind::random_view: return "random:" + set + "@" + std::to_string(index);
    case Kind::max_list: return "max_list:" + set;
  }
  return "default";
}

CameraSpec parse_camera_spec(const std::string& text) {
  CameraSpec spec;
  if (text == "default") return spec;
  auto parse_set = [&](const std::string& rest, bool allow_index) {
    const auto colon = rest.find(':');
    if (colon == std::string::npos) throw std::invalid_argument("");
    const auto at = rest.find('@', colon);
    if (at != std::string::npos && !allow_index) throw std::invalid_argument("");
    spec.count = number(text, rest.substr(0, colon), "viewpoint count", 1, kMaxViewpoints);
    spec.seed = number(text, rest.substr(colon + 1, at == std::string::npos ? std::string::npos : at - colon - 1),
                       "seed", 0, UINT32_MAX);
    if (at != std::string::npos) {
      spec.kind = CameraSpec::Kind::random_view;
      spec.index = number(text, rest.substr(at + 1), "viewpoint index", 0, spec.count - 1);
    }
  };
  try {
    if (text.rfind("random:", 0) == 0) {
      spec.kind = CameraSpec::Kind::random_set;
      parse_set(text.substr(7), true);
      return spec;
    }
    if (text == "max_list") {
      spec.kind = CameraSpec::Kind::max_list;
      spec.count = kDefaultMaxListCount;
      return spec;
    }
    if (text.rfind("max_list:", 0) == 0) {
      spec.kind = CameraSpec::Kind::max_list;
      parse_set(text.substr(9), false);
      return spec;
    }
  } catch (const std::invalid_argument& e) {
    if (std::string(e.what()).empty()) {
      throw std::invalid_argument("camera '" + text + "' is not of the form random:N:SEED, random:N:SEED@I or "
                                  "max_list:N:SEED");
    }
    throw;
  }
  throw std::invalid_argument("camera '" + text + "' is not default, random:N:SEED, random:N:SEED@I, max_list or "
                              "max_list:N:SEED");
}

std::vector<std::string> expand_camera_spec(const std::string& text) {
  CameraSpec spec = parse_camera_spec(text);
  if (spec.kind != CameraSpec::Kind::random_set) return {spec.text()};
  std::vector<std::string> views;
  spec.kind = CameraSpec::Kind::random_view;
  for (uint32_t i = 0; i < spec.count; ++i) {
    spec.index = i;
    views.push_back(spec.text());
  }
  return views;
}

Camera random_viewpoint(const BoundingSphere& sphere, uint32_t seed, uint32_t index) {
  std::mt19937 rng(seed);
  rng.discard(2ull * index);
  // Uniform on the unit sphere: z uniform in [-1, 1], longitude uniform.
  const double z = 1.0 - 2.0 * unit(rng);
  const double longitude = 2.0 * 3.14159265358979323846 * unit(rng);
  const double ring = std::sqrt(std::max(0.0, 1.0 - z * z));
  const glm::vec3 direction(float(ring * std::cos(longitude)), float(ring * std::sin(longitude)), float(z));
  return frame_bounding_sphere(sphere, direction);
}

Camera camera_for_spec(const Scene& scene, const CameraSpec& spec) {
  switch (spec.kind) {
    case CameraSpec::Kind::scene_default: return scene.camera;
    case CameraSpec::Kind::random_view: return random_viewpoint(scene.bounds(), spec.seed, spec.index);
    case CameraSpec::Kind::random_set:
      throw std::invalid_argument("camera '" + spec.text() + "' is a set of viewpoints; a run takes one of them");
    case CameraSpec::Kind::max_list:
      throw std::invalid_argument("camera '" + spec.text() + "' is chosen by measuring depth complexity on the GPU");
  }
  return scene.camera;
}

}  // namespace oit
