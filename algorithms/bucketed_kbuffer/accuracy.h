#pragma once
// Read-back statistics of the bucketed k-buffer, computed once after the
// timed frames (Technique::counters), never inside a timed stage.
#include <cstdint>
#include <vector>

namespace oit::bkb {

constexpr uint32_t kEmptyKey = 0xffffffffu;

// Per-slot contents of the buffers after a frame (pixel-major, K per pixel).
struct SlotReadback {
  std::vector<uint32_t> keys;      // Z (shape-major after the sort pass)
  std::vector<uint32_t> normals;   // packed normal, 0 = no data stored
  std::vector<uint32_t> features;  // kappa (float16) | found mask << 16
  std::vector<uint32_t> links;     // measure_accuracy only
  std::vector<float> expected;     // analytic k1 + k2, measure_accuracy only
  std::vector<float> estimated;    // screen-space k1 + k2, measure_accuracy only
};

struct SlotStatistics {
  uint64_t stored = 0;        // slots holding a kept fragment with its data
  uint64_t store_misses = 0;  // kept in Z but no data arrived in the data pass
  uint64_t links = 0;         // neighbour links found (all four directions)
  uint32_t link_checksum = 0; // FNV-1a over the link words of stored slots
  uint64_t kept = 0;            // non-empty keys in Z (stored + store_misses)
  uint64_t covered_pixels = 0;  // pixels with at least one kept fragment
  uint64_t buckets = 0;         // runs of equal shape ids in the shape-major lists
};
// k: slots per pixel; shape_bits: the shape id's share of the 32-bit key
// (the high bits after the sort pass).
SlotStatistics slot_statistics(const SlotReadback& slots, int k, int shape_bits);

struct CurvatureAccuracy {
  uint64_t samples = 0;  // fragments measured
  double kappa_mean_error = 0.0, kappa_max_error = 0.0;
  double curvature_mean_relative_error = 0.0, curvature_max_relative_error = 0.0;
};
// Compares kappa = tanh(scale * (k1 + k2)) with the analytic value over the
// fragments away from silhouettes: all four neighbours linked and the
// viewer-facing normal within 60 degrees of the view axis (n_z >= 0.5).
CurvatureAccuracy curvature_accuracy(const SlotReadback& slots, double curvature_scale);

}  // namespace oit::bkb
