#pragma once
// Scalar fields as colour images (blue = 0 ... red = max), for per-pixel
// error and list-length maps.
#include <vector>

#include "harness/core/image.h"

namespace oit {

// `values` has one entry per pixel, rows bottom-up like Image. Values are
// scaled by 1/max_value (max_value <= 0: the largest value); alpha is 1.
Image heatmap(const std::vector<float>& values, int width, int height, float max_value = 0.0f);

// `values` mapped linearly from [low, high] (blue) .. red, clamped; NaN
// values (no value at that pixel) are black. Rows bottom-up like Image.
Image heatmap_range(const std::vector<float>& values, int width, int height, float low, float high);

// Per-pixel largest absolute channel difference between two images, as a
// heatmap scaled to its own maximum.
Image error_heatmap(const Image& image, const Image& reference);

}  // namespace oit
