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
  std::vector<uint32_t> features;  // kappa (float16) | found mask << 16; empty: none kept
  std::vector<uint32_t> links;     // measure_accuracy only
  std::vector<float> expected;     // analytic k1 + k2, measure_accuracy only
  std::vector<float> estimated;    // screen-space k1 + k2, measure_accuracy only
  // measure_accuracy only, 4 words per slot: surface id, u and v (float
  // bits), fwidth(uv) as half2 (the uv footprint of one pixel).
  std::vector<uint32_t> truth;
};

struct SlotStatistics {
  uint64_t stored = 0;        // slots holding a kept fragment with its data
  uint64_t store_misses = 0;  // kept in Z but no data arrived in the data pass
  uint64_t links = 0;         // neighbour links found (all four directions; 0 without features)
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

struct LinkAccuracy {
  uint64_t links = 0;           // links of stored fragments (all four directions)
  uint64_t correct_links = 0;   // links joining true surface neighbours
  uint64_t true_neighbors = 0;  // (fragment, direction) pairs whose adjacent pixel holds one
  double precision = 1.0;       // correct_links / links (1 without links)
  double recall = 1.0;          // correct_links / true_neighbors (1 without true neighbours)
};
// Tolerance of a correct link, in pixel footprints (illustration_buffer's
// default accuracy_footprints).
constexpr double kLinkFootprints = 1.5;
// Precision and recall of the links against the parametric ground truth, as
// illustration_buffer measures them: a link i -> j is correct when both
// fragments lie on the same surface and |du|, |dv| (wrapped on [0, 1)) are at
// most `footprints` times the larger of the two fragments' fwidth(uv). Recall
// counts the (fragment, direction) pairs, inside the image, for which the
// adjacent pixel holds such a fragment. Needs keys, normals, links and truth.
LinkAccuracy link_accuracy(const SlotReadback& slots, int width, int height, int k, double footprints);

// Links i -> j whose target links back (j's link in the opposite direction
// is i): with reverse_check every link is mutual up to exact ties of eps;
// without it a fragment may link to a candidate that prefers another.
// Needs links (measure_accuracy); 0 without them.
uint64_t mutual_links(const SlotReadback& slots, int width, int height, int k);

}  // namespace oit::bkb
