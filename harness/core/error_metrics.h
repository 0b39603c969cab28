#pragma once
#include "core/image.h"

namespace oit {

// Difference of an image from the reference over all four channels.
struct ImageError {
  double max_abs = 0.0;
  double rmse = 0.0;
  double psnr_db = 0.0;  // peak 1.0; +inf when identical
};

// Throws when the sizes differ.
ImageError compare_images(const Image& image, const Image& reference);

}  // namespace oit
