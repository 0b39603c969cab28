#pragma once
#include <cstdint>
#include <vector>

#include "scenes/cameras.h"
#include "harness/output/heatmap.h"
#include "harness/output/image.h"
#include "harness/toolkit/scene_gpu.h"

namespace oit {

// Depth complexity of one view: fragments per pixel (the length of each
// pixel's fragment list).
struct DepthComplexity {
  int width = 0, height = 0;
  std::vector<uint32_t> per_pixel;  // bottom-up rows
  uint64_t fragments = 0;
  uint32_t max = 0;
  double mean = 0.0;            // over all pixels
  uint64_t covered_pixels = 0;  // pixels with at least one fragment
  // Complexity coverage Psi (pastyrik2016 section 4.2, Fig. 9): the share of
  // ALL pixels of the image whose list is longer than 2/3 of the longest
  // list (strictly: 3 * length > 2 * max). 0 for an empty view. The paper
  // does not say whether empty pixels count; counting them makes Psi
  // comparable across models framed in the same image.
  double psi = 0.0;
};

// Renders the scene once with a counting shader (no depth test, no culling).
DepthComplexity measure_depth_complexity(const SceneGpu& scene, const glm::mat4& view, const glm::mat4& projection,
                                         int width, int height);

// Fills fragments, max, mean, covered_pixels and psi from per_pixel.
void summarize_depth_complexity(DepthComplexity& complexity);

// histogram[n] = pixels whose list has n fragments, n = 0 .. max.
std::vector<uint64_t> list_length_histogram(const DepthComplexity& complexity);

// Consecutive list lengths merged into at most `max_bins` bins of equal
// width (the last may be narrower), for printing.
struct HistogramBin {
  uint32_t first = 0, last = 0;  // list lengths, inclusive
  uint64_t pixels = 0;
};
std::vector<HistogramBin> binned_histogram(const std::vector<uint64_t>& histogram, size_t max_bins);

// List lengths as colours (viridis, heatmap.h), 0 to the longest list,
// like the heatmaps of pastyrik2016 Fig. 10; list_length_scale is that
// scale, for the colour bar.
ColourScale list_length_scale(const DepthComplexity& complexity);
Image list_length_heatmap(const DepthComplexity& complexity);

// The max_list camera: among the viewpoints of spec's random set, the one
// whose longest list (at probe_size x probe_size) is longest; ties go to
// the larger mean, then the lower index.
struct ChosenViewpoint {
  uint32_t index = 0;
  Camera camera;
  uint32_t max_list = 0;
};
ChosenViewpoint choose_max_list_camera(const SceneGpu& scene, const CameraSpec& spec, int probe_size = 256);

// The camera a run uses: the scene's own, a random viewpoint, or max_list.
Camera resolve_camera(const SceneGpu& scene, const std::string& camera_spec);

}  // namespace oit
