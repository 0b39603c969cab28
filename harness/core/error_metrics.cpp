#include "core/error_metrics.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace oit {

ImageError compare_images(const Image& image, const Image& reference) {
  if (image.width != reference.width || image.height != reference.height) {
    throw std::invalid_argument("cannot compare a " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + " image with a " + std::to_string(reference.width) +
                                "x" + std::to_string(reference.height) + " reference");
  }
  ImageError error;
  double squared = 0.0;
  for (size_t i = 0; i < image.rgba.size(); ++i) {
    const double d = std::abs(double(image.rgba[i]) - double(reference.rgba[i]));
    // A NaN anywhere must not hide: it makes the error infinite.
    if (!std::isfinite(d)) {
      error.max_abs = error.rmse = std::numeric_limits<double>::infinity();
      error.psnr_db = -std::numeric_limits<double>::infinity();
      return error;
    }
    error.max_abs = std::max(error.max_abs, d);
    squared += d * d;
  }
  error.rmse = image.rgba.empty() ? 0.0 : std::sqrt(squared / double(image.rgba.size()));
  error.psnr_db = error.rmse > 0.0 ? -20.0 * std::log10(error.rmse) : std::numeric_limits<double>::infinity();
  return error;
}

}  // namespace oit
