#include "algorithms/illustration_buffer/accuracy.h"

#include <glm/packing.hpp>  // unpackHalf2x16 (GLSL core packing)

#include <algorithm>
#include <cmath>

namespace oit::illustration_buffer {
namespace {

constexpr int kDx[4] = {-1, 1, 0, 0};
constexpr int kDy[4] = {0, 0, -1, 1};
// Below this a footprint is treated as this (flat-shaded or degenerate uv).
constexpr float kSmallestFootprint = 1e-6f;

struct SurfacePoint {
  uint32_t surface;
  glm::vec2 uv;
  glm::vec2 footprint;
};

SurfacePoint point_of(const TruthRecord& t) {
  return {t.surface, glm::vec2(t.u, t.v), glm::unpackHalf2x16(t.footprint)};
}

float wrapped_distance(float a, float b) {
  const float d = std::abs(a - b);
  return std::min(d, 1.0f - d);
}

uint32_t link_checksum(int width, const std::vector<uint32_t>& first, const std::vector<uint32_t>& count,
                       const std::vector<SortedRecord>& sorted) {
  uint32_t hash = 2166136261u;
  for (size_t pixel = 0; pixel < first.size(); ++pixel) {
    for (uint32_t s = first[pixel]; s < first[pixel] + count[pixel] && s < sorted.size(); ++s) {
      for (int d = 0; d < 4; ++d) {
        uint32_t link = sorted[s].links[d];
        if (link != kNoNeighbor && link != kOffImage) {
          const int64_t other = int64_t(pixel) + kDx[d] + int64_t(kDy[d]) * width;
          link -= other >= 0 && size_t(other) < first.size() ? first[size_t(other)] : 0u;
        }
        for (int byte = 0; byte < 4; ++byte) hash = (hash ^ ((link >> (8 * byte)) & 0xffu)) * 16777619u;
      }
    }
  }
  return hash;
}

}  // namespace

NeighborStatistics neighbor_statistics(int width, int height, const std::vector<uint32_t>& first,
                                       const std::vector<uint32_t>& count, const std::vector<SortedRecord>& sorted,
                                       const std::vector<TruthRecord>& truth, double footprints) {
  NeighborStatistics stats;
  stats.measured = !truth.empty();
  auto truth_of = [&](uint32_t s) { return point_of(truth.at(sorted[s].geometry[3])); };
  auto adjacent = [&](const SurfacePoint& a, const SurfacePoint& b) {
    if (a.surface != b.surface) return false;
    const glm::vec2 tolerance =
        float(footprints) * glm::max(glm::max(a.footprint, b.footprint), glm::vec2(kSmallestFootprint));
    return wrapped_distance(a.uv.x, b.uv.x) <= tolerance.x && wrapped_distance(a.uv.y, b.uv.y) <= tolerance.y;
  };
  for (uint32_t s = 0; s < sorted.size(); ++s) {
    const SortedRecord& record = sorted[s];
    const uint32_t pixel = record.key[3];
    const int x = int(pixel % uint32_t(width)), y = int(pixel / uint32_t(width));
    bool silhouette = false;
    for (int d = 0; d < 4; ++d) {
      const uint32_t link = record.links[d];
      if (link == kOffImage) continue;
      silhouette = silhouette || link == kNoNeighbor;
      if (link != kNoNeighbor) ++stats.links[size_t(d)];
      if (!stats.measured) continue;
      const int nx = x + kDx[d], ny = y + kDy[d];
      if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
      const SurfacePoint mine = truth_of(s);
      const uint32_t other = uint32_t(ny) * uint32_t(width) + uint32_t(nx);
      bool exists = false;
      for (uint32_t j = first[other]; j < first[other] + count[other] && !exists; ++j)
        exists = adjacent(mine, truth_of(j));
      stats.true_neighbors += exists;
      if (link != kNoNeighbor && link < sorted.size()) stats.correct_links += adjacent(mine, truth_of(link));
    }
    stats.silhouette_fragments += silhouette;
  }
  stats.link_checksum = link_checksum(width, first, count, sorted);
  if (stats.measured) {
    uint64_t links = 0;
    for (uint64_t n : stats.links) links += n;
    // No links / no true neighbours: nothing wrong was claimed / nothing was missed.
    stats.precision = links > 0 ? double(stats.correct_links) / double(links) : 1.0;
    stats.recall = stats.true_neighbors > 0 ? double(stats.correct_links) / double(stats.true_neighbors) : 1.0;
  }
  return stats;
}

}  // namespace oit::illustration_buffer
