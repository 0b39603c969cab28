#include "harness/core/heatmap.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace oit {
namespace {

// The classic "jet" ramp: dark blue (0) -> cyan -> yellow -> dark red (1).
void ramp(float t, float* rgb) {
  t = std::clamp(std::isfinite(t) ? t : 1.0f, 0.0f, 1.0f);
  for (int c = 0; c < 3; ++c) rgb[c] = std::clamp(1.5f - std::abs(4.0f * t - float(3 - c)), 0.0f, 1.0f);
}

}  // namespace

Image heatmap(const std::vector<float>& values, int width, int height, float max_value) {
  if (values.size() != size_t(width) * size_t(height)) throw std::invalid_argument("heatmap: value count != pixels");
  if (max_value <= 0.0f)
    for (float v : values)
      if (std::isfinite(v)) max_value = std::max(max_value, v);
  Image image{width, height, std::vector<float>(values.size() * 4, 1.0f)};
  for (size_t p = 0; p < values.size(); ++p) ramp(max_value > 0.0f ? values[p] / max_value : 0.0f, &image.rgba[4 * p]);
  return image;
}

Image heatmap_range(const std::vector<float>& values, int width, int height, float low, float high) {
  if (values.size() != size_t(width) * size_t(height))
    throw std::invalid_argument("heatmap_range: value count != pixels");
  const float span = high > low ? high - low : 1.0f;
  Image image{width, height, std::vector<float>(values.size() * 4, 1.0f)};
  for (size_t p = 0; p < values.size(); ++p) {
    if (std::isnan(values[p])) {
      for (int c = 0; c < 3; ++c) image.rgba[4 * p + size_t(c)] = 0.0f;
      continue;
    }
    ramp((values[p] - low) / span, &image.rgba[4 * p]);
  }
  return image;
}

Image error_heatmap(const Image& image, const Image& reference) {
  if (image.width != reference.width || image.height != reference.height)
    throw std::invalid_argument("error_heatmap: image and reference sizes differ");
  std::vector<float> error(size_t(image.width) * size_t(image.height), 0.0f);
  for (size_t p = 0; p < error.size(); ++p)
    for (size_t c = 0; c < 4; ++c)
      error[p] = std::max(error[p], std::abs(image.rgba[4 * p + c] - reference.rgba[4 * p + c]));
  return heatmap(error, image.width, image.height);
}

}  // namespace oit
