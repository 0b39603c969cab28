#include "harness/output/error_metrics.h"

#include "harness/output/flip.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace oit {
namespace {

// Rec. 709 luma of the composite colour: SSIM compares structure as seen.
std::vector<double> luma(const Image& image) {
  std::vector<double> y(size_t(image.width) * size_t(image.height));
  for (size_t p = 0; p < y.size(); ++p) {
    const float* c = &image.rgba[4 * p];
    y[p] = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
  }
  return y;
}

// Separable Gaussian blur (sigma 1.5, radius 5: the 11x11 window of Wang et
// al. 2004), clamping at the borders.
std::vector<double> blur(const std::vector<double>& in, int width, int height) {
  constexpr int kRadius = 5;
  double weights[2 * kRadius + 1], sum = 0.0;
  for (int i = -kRadius; i <= kRadius; ++i) sum += weights[i + kRadius] = std::exp(-0.5 * i * i / (1.5 * 1.5));
  for (double& w : weights) w /= sum;
  std::vector<double> rows(in.size()), out(in.size());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double v = 0.0;
      for (int i = -kRadius; i <= kRadius; ++i) v += weights[i + kRadius] * in[size_t(y) * width + std::clamp(x + i, 0, width - 1)];
      rows[size_t(y) * width + x] = v;
    }
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double v = 0.0;
      for (int i = -kRadius; i <= kRadius; ++i) v += weights[i + kRadius] * rows[size_t(std::clamp(y + i, 0, height - 1)) * width + x];
      out[size_t(y) * width + x] = v;
    }
  return out;
}

}  // namespace

double structural_similarity(const Image& image, const Image& reference) {
  const int w = image.width, h = image.height;
  const std::vector<double> a = luma(image), b = luma(reference);
  std::vector<double> aa(a.size()), bb(a.size()), ab(a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    aa[i] = a[i] * a[i];
    bb[i] = b[i] * b[i];
    ab[i] = a[i] * b[i];
  }
  const auto mu_a = blur(a, w, h), mu_b = blur(b, w, h), m_aa = blur(aa, w, h), m_bb = blur(bb, w, h),
             m_ab = blur(ab, w, h);
  constexpr double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;  // dynamic range 1
  double total = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    const double var_a = m_aa[i] - mu_a[i] * mu_a[i], var_b = m_bb[i] - mu_b[i] * mu_b[i];
    const double cov = m_ab[i] - mu_a[i] * mu_b[i];
    total += ((2 * mu_a[i] * mu_b[i] + c1) * (2 * cov + c2)) /
             ((mu_a[i] * mu_a[i] + mu_b[i] * mu_b[i] + c1) * (var_a + var_b + c2));
  }
  return a.empty() ? 1.0 : total / double(a.size());
}

ImageError compare_images(const Image& image, const Image& reference) {
  if (image.width != reference.width || image.height != reference.height) {
    throw std::invalid_argument("cannot compare a " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + " image with a " + std::to_string(reference.width) +
                                "x" + std::to_string(reference.height) + " reference");
  }
  ImageError error;
  double squared = 0.0;
  size_t pixels_over = 0;
  for (size_t p = 0; 4 * p < image.rgba.size(); ++p) {
    bool over = false;
    for (size_t c = 0; c < 4; ++c) {
      const size_t i = 4 * p + c;
      const double d = std::abs(double(image.rgba[i]) - double(reference.rgba[i]));
      // A NaN anywhere must not hide: it makes the error infinite.
      if (!std::isfinite(d)) {
        error.max_abs = error.rmse = std::numeric_limits<double>::infinity();
        error.psnr_db = -std::numeric_limits<double>::infinity();
        error.ssim = -1.0;
        error.flip = 1.0;
        error.share_over_1_255 = 1.0;
        return error;
      }
      error.max_abs = std::max(error.max_abs, d);
      squared += d * d;
      over = over || d > 1.0 / 255.0;
    }
    pixels_over += over;
  }
  const size_t pixels = image.rgba.size() / 4;
  error.rmse = image.rgba.empty() ? 0.0 : std::sqrt(squared / double(image.rgba.size()));
  error.psnr_db = error.rmse > 0.0 ? -20.0 * std::log10(error.rmse) : std::numeric_limits<double>::infinity();
  error.share_over_1_255 = pixels ? double(pixels_over) / double(pixels) : 0.0;
  error.ssim = structural_similarity(image, reference);
  error.flip = mean_flip(image, reference);
  return error;
}

}  // namespace oit
