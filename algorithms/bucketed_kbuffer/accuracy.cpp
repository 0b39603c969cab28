#include "accuracy.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace oit::bkb {
namespace {

constexpr uint32_t kAllFourNeighbours = 0xfu;

double normal_z(uint32_t word) {
  const double x = double(word & 0x7fffu) * (2.0 / 32767.0) - 1.0;
  const double y = double((word >> 15) & 0x7fffu) * (2.0 / 32767.0) - 1.0;
  const double z = std::sqrt(std::max(0.0, 1.0 - x * x - y * y));
  return (word & 0x40000000u) ? -z : z;
}

}  // namespace

SlotStatistics slot_statistics(const SlotReadback& slots, int k, int shape_bits) {
  SlotStatistics s;
  // Buckets per pixel show whether the bucketed query can help at all: with
  // one bucket per pixel (one object) it visits the whole list, like brute force.
  for (size_t base = 0; base + size_t(k) <= slots.keys.size(); base += size_t(k)) {
    for (size_t i = base; i < base + size_t(k) && slots.keys[i] != kEmptyKey; ++i) {
      const uint32_t shape = slots.keys[i] >> (32 - shape_bits);
      s.buckets += i == base || shape != (slots.keys[i - 1] >> (32 - shape_bits));
      s.covered_pixels += i == base;
      ++s.kept;
    }
  }
  uint32_t hash = 2166136261u;
  for (size_t i = 0; i < slots.keys.size(); ++i) {
    if (slots.keys[i] == kEmptyKey) continue;
    if (slots.normals[i] == 0u) {
      ++s.store_misses;
      continue;
    }
    ++s.stored;
    s.links += uint64_t(std::popcount((slots.features[i] >> 16) & kAllFourNeighbours));
    if (!slots.links.empty()) {
      for (int byte = 0; byte < 4; ++byte) hash = (hash ^ ((slots.links[i] >> (8 * byte)) & 0xffu)) * 16777619u;
    }
  }
  s.link_checksum = slots.links.empty() ? 0u : hash;
  return s;
}

CurvatureAccuracy curvature_accuracy(const SlotReadback& slots, double curvature_scale) {
  CurvatureAccuracy a;
  uint64_t relative_samples = 0;
  for (size_t i = 0; i < slots.keys.size(); ++i) {
    if (slots.keys[i] == kEmptyKey || slots.normals[i] == 0u) continue;
    if (((slots.features[i] >> 16) & kAllFourNeighbours) != kAllFourNeighbours) continue;
    if (normal_z(slots.normals[i]) < 0.5) continue;
    const double estimated = slots.estimated[i], expected = slots.expected[i];
    if (!std::isfinite(estimated) || !std::isfinite(expected)) continue;
    const double error = std::abs(std::tanh(curvature_scale * estimated) - std::tanh(curvature_scale * expected));
    ++a.samples;
    a.kappa_mean_error += error;
    a.kappa_max_error = std::max(a.kappa_max_error, error);
    if (std::abs(expected) > 1e-6) {
      const double relative = std::abs(estimated - expected) / std::abs(expected);
      ++relative_samples;
      a.curvature_mean_relative_error += relative;
      a.curvature_max_relative_error = std::max(a.curvature_max_relative_error, relative);
    }
  }
  if (a.samples > 0) a.kappa_mean_error /= double(a.samples);
  if (relative_samples > 0) a.curvature_mean_relative_error /= double(relative_samples);
  return a;
}

}  // namespace oit::bkb
