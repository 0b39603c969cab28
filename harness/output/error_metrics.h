#pragma once
#include "harness/output/image.h"

namespace oit {

// Difference of an image from the reference over all four channels.
struct ImageError {
  double max_abs = 0.0;
  double rmse = 0.0;
  double psnr_db = 0.0;  // peak 1.0; +inf when identical
  double ssim = 1.0;     // mean SSIM of the luma (Wang et al. 2004, 11x11 Gaussian window)
  double flip = 0.0;     // mean LDR-FLIP of the RGB (Andersson et al. 2020, flip.h): 0 same .. 1
  double share_over_1_255 = 0.0;  // share of pixels with a channel off by more than 1/255 (visible in 8 bits)
};

// Throws when the sizes differ.
ImageError compare_images(const Image& image, const Image& reference);
double structural_similarity(const Image& image, const Image& reference);

}  // namespace oit
