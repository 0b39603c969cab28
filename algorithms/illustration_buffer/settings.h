#pragma once
// The validated parameters of the illustration buffer, typed.
#include <cstdint>
#include <memory>

#include "harness/core/technique.h"

namespace oit::illustration_buffer {

// heuristic_merge: the heuristic's candidate found by a walk of the
// depth-sorted list (the same links, fewer candidates scored).
enum class NeighborSearch { heuristic, heuristic_merge, triangle_index };
// Which of carnecky2013's fields modulate the opacity: none (plain alpha
// blending; no neighbour search, no stylize), beta (silhouette), gamma
// (halo) or both.
enum class Modulation { none, silhouette, halo, silhouette_halo };
enum class Profile { none, exponential, power };  // eq. 10 / eq. 11

struct Settings {
  NeighborSearch neighbors = NeighborSearch::triangle_index;
  Modulation modulation = Modulation::silhouette_halo;
  bool adaptive_alpha = false;  // eq. 5 instead of eq. 4
  int iterations = 20;
  float lambda_alpha = 1.0f, lambda_beta = 0.05f, lambda_gamma = 0.1f;
  Profile profile = Profile::none;
  float exponential_p = 3.0f, power_p = 0.3f;
  float weight_z = 1.0f, weight_n = 1.0f;
  bool weld_vertices = true;
  uint32_t max_per_pixel = 64;
  uint64_t initial_nodes_per_pixel = 8;
  bool measure_accuracy = true;
  double accuracy_footprints = 1.5;

  bool heuristic() const { return neighbors != NeighborSearch::triangle_index; }
  bool uses_beta() const { return modulation == Modulation::silhouette || modulation == Modulation::silhouette_halo; }
  bool uses_gamma() const { return modulation == Modulation::halo || modulation == Modulation::silhouette_halo; }
};

Settings settings_from(const ParamSet& params);
std::unique_ptr<Technique> make_illustration_buffer(const Settings& settings);
// GPU storage of a frame of `content` (TechniqueDescriptor::storage_need).
StorageNeed storage_need(const Settings& settings, const FrameContent& content);

}  // namespace oit::illustration_buffer
