#pragma once
// Neighbour statistics of one frame, computed on the CPU from read-back
// buffers (in counters(), outside the timed frames): links per direction,
// silhouette fragments, and precision/recall of the links against the
// parametric ground truth (surface id and (u, v) of every fragment).
#include <array>
#include <cstdint>
#include <vector>

#include "algorithms/illustration_buffer/bindings.h"

namespace oit::illustration_buffer {

constexpr uint32_t kNoNeighbor = IB_NONE;
constexpr uint32_t kOffImage = IB_OFF_IMAGE;

// IbSortedSearch (fragData2) and IbSortedShade (fragData3) of ib_storage.glsl, 32 B each.
struct SortedSearchRecord {
  uint32_t key[4];       // depth bits, stable triangle id, object id, pixel
  uint32_t geometry[4];  // packed normal, dz/dx bits, dz/dy bits (triangle_index: the triangle's vertex
                         // indices; neither with modulation=none), fill record index
};
static_assert(sizeof(SortedSearchRecord) == 32);
struct SortedShadeRecord {
  float color[4];
  uint32_t links[4];  // left, right, down, up
};
static_assert(sizeof(SortedShadeRecord) == 32);

// One sorted fragment, both halves joined on the CPU (read-back only).
struct SortedRecord {
  float color[4];
  uint32_t key[4];       // depth bits, stable triangle id, object id, pixel
  uint32_t geometry[4];  // as SortedSearchRecord::geometry
  uint32_t links[4];     // left, right, down, up
};

inline SortedRecord join(const SortedSearchRecord& search, const SortedShadeRecord& shade) {
  SortedRecord r;
  for (int i = 0; i < 4; ++i) {
    r.color[i] = shade.color[i];
    r.key[i] = search.key[i];
    r.geometry[i] = search.geometry[i];
    r.links[i] = shade.links[i];
  }
  return r;
}

// The fill's ground-truth record (16 B): surface id, u, v bits, fwidth(uv) as half2.
struct TruthRecord {
  uint32_t surface;
  float u, v;
  uint32_t footprint;
};
static_assert(sizeof(TruthRecord) == 16);

struct NeighborStatistics {
  std::array<uint64_t, 4> links{};  // left, right, down, up
  uint64_t silhouette_fragments = 0;  // a missing neighbour inside the image
  bool measured = false;              // precision/recall computed
  uint64_t correct_links = 0;         // links joining true surface neighbours
  uint64_t true_neighbors = 0;        // (fragment, direction) pairs that have one
  double precision = 0.0;
  double recall = 0.0;
  // FNV-1a over every link as the position in the adjacent pixel's list
  // (or kNoNeighbor / kOffImage), pixels in image order and fragments in
  // list order: equal for equal links, whatever ranges the sort allocated.
  uint32_t link_checksum = 0;
};

// `first`/`count`: each pixel's range in `sorted`. `truth` may be empty
// (then only links and silhouettes are counted). A link i -> j is correct
// when both lie on the same surface and |du|, |dv| (wrapped: parameters
// are periodic on [0, 1) for spheres, tori, cylinders) are at most
// `footprints` times the larger of the two fragments' fwidth(uv).
NeighborStatistics neighbor_statistics(int width, int height, const std::vector<uint32_t>& first,
                                       const std::vector<uint32_t>& count, const std::vector<SortedRecord>& sorted,
                                       const std::vector<TruthRecord>& truth, double footprints);

}  // namespace oit::illustration_buffer
