#include "algorithms/bucketed_kbuffer/accuracy.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include <glm/packing.hpp>  // unpackHalf2x16 (GLSL core packing)

namespace oit::bkb {
namespace {

constexpr uint32_t kAllFourNeighbours = 0xfu;

double normal_z(uint32_t word) {
  const double x = double(word & 0x7fffu) * (2.0 / 32767.0) - 1.0;
  const double y = double((word >> 15) & 0x7fffu) * (2.0 / 32767.0) - 1.0;
  const double z = std::sqrt(std::max(0.0, 1.0 - x * x - y * y));
  return (word & 0x40000000u) ? -z : z;
}

struct SurfacePoint {
  uint32_t surface;
  glm::vec2 uv, footprint;
};

SurfacePoint surface_point(const std::vector<uint32_t>& truth, size_t slot) {
  return {truth[4 * slot], glm::vec2(std::bit_cast<float>(truth[4 * slot + 1]), std::bit_cast<float>(truth[4 * slot + 2])),
          glm::unpackHalf2x16(truth[4 * slot + 3])};
}

float wrapped_distance(float a, float b) {
  const float d = std::abs(a - b) - std::floor(std::abs(a - b));  // parameters are periodic on [0, 1)
  return std::min(d, 1.0f - d);
}

}  // namespace

LinkAccuracy link_accuracy(const SlotReadback& slots, int width, int height, int k, double footprints) {
  constexpr int kDx[4] = {-1, 1, 0, 0};  // left, right, down, up: the byte order of a link word
  constexpr int kDy[4] = {0, 0, -1, 1};
  constexpr float kSmallestFootprint = 1e-6f;  // flat-shaded or degenerate uv
  LinkAccuracy a;
  const size_t slot_count = size_t(width) * size_t(height) * size_t(k);
  if (slots.truth.size() < 4 * slot_count || slots.links.size() < slot_count) return a;
  auto has_data = [&](size_t slot) { return slots.keys[slot] != kEmptyKey && slots.normals[slot] != 0u; };
  auto adjacent = [&](const SurfacePoint& p, const SurfacePoint& q) {
    if (p.surface != q.surface) return false;
    const glm::vec2 tolerance =
        float(footprints) * glm::max(glm::max(p.footprint, q.footprint), glm::vec2(kSmallestFootprint));
    return wrapped_distance(p.uv.x, q.uv.x) <= tolerance.x && wrapped_distance(p.uv.y, q.uv.y) <= tolerance.y;
  };
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const size_t base = (size_t(y) * size_t(width) + size_t(x)) * size_t(k);
      for (size_t i = base; i < base + size_t(k); ++i) {
        if (!has_data(i)) continue;
        const SurfacePoint mine = surface_point(slots.truth, i);
        for (int d = 0; d < 4; ++d) {
          const int nx = x + kDx[d], ny = y + kDy[d];
          if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
          const size_t other = (size_t(ny) * size_t(width) + size_t(nx)) * size_t(k);
          bool exists = false;
          for (size_t j = other; j < other + size_t(k) && !exists; ++j)
            exists = has_data(j) && adjacent(mine, surface_point(slots.truth, j));
          a.true_neighbors += exists;
          const uint32_t link = (slots.links[i] >> (8 * d)) & 0xffu;
          if (link == 0xffu) continue;
          ++a.links;
          const size_t j = other + link;
          a.correct_links += link < uint32_t(k) && has_data(j) && adjacent(mine, surface_point(slots.truth, j));
        }
      }
    }
  }
  a.precision = a.links > 0 ? double(a.correct_links) / double(a.links) : 1.0;
  a.recall = a.true_neighbors > 0 ? double(a.correct_links) / double(a.true_neighbors) : 1.0;
  return a;
}

uint64_t mutual_links(const SlotReadback& slots, int width, int height, int k) {
  constexpr int kDx[4] = {-1, 1, 0, 0};  // left, right, down, up: the byte order of a link word
  constexpr int kDy[4] = {0, 0, -1, 1};
  constexpr int kOpposite[4] = {1, 0, 3, 2};
  const size_t slot_count = size_t(width) * size_t(height) * size_t(k);
  if (slots.links.size() < slot_count || slots.keys.size() < slot_count) return 0;
  uint64_t mutual = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const size_t base = (size_t(y) * size_t(width) + size_t(x)) * size_t(k);
      for (size_t i = base; i < base + size_t(k) && slots.keys[i] != kEmptyKey; ++i) {
        if (slots.normals[i] == 0u) continue;
        for (int d = 0; d < 4; ++d) {
          const uint32_t link = (slots.links[i] >> (8 * d)) & 0xffu;
          const int nx = x + kDx[d], ny = y + kDy[d];
          if (link >= uint32_t(k) || nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
          const size_t j = (size_t(ny) * size_t(width) + size_t(nx)) * size_t(k) + link;
          mutual += ((slots.links[j] >> (8 * kOpposite[d])) & 0xffu) == uint32_t(i - base);
        }
      }
    }
  }
  return mutual;
}

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
    if (!slots.features.empty()) s.links += uint64_t(std::popcount((slots.features[i] >> 16) & kAllFourNeighbours));
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
