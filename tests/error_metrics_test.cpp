// Image error against the reference: max, RMSE, PSNR, SSIM, and the share
// of pixels with a visible (8-bit) difference.
#include <gtest/gtest.h>

#include <cmath>

#include "harness/output/error_metrics.h"

namespace oit {
namespace {

Image gradient(int w, int h) {
  Image image{w, h, std::vector<float>(size_t(w) * h * 4)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 4; ++c) image.rgba[(size_t(y) * w + x) * 4 + c] = float(x + y) / float(w + h);
  return image;
}

TEST(ErrorMetrics, IdenticalImagesAreExact) {
  const Image a = gradient(16, 8);
  const ImageError e = compare_images(a, a);
  EXPECT_EQ(e.max_abs, 0.0);
  EXPECT_EQ(e.rmse, 0.0);
  EXPECT_TRUE(std::isinf(e.psnr_db));
  EXPECT_NEAR(e.ssim, 1.0, 1e-12);
  EXPECT_EQ(e.share_over_1_255, 0.0);
}

TEST(ErrorMetrics, OnePixelOffByTwoLevelsIsOneVisiblePixel) {
  const Image a = gradient(16, 8);
  Image b = a;
  b.rgba[4 * 5 + 1] += 2.0f / 255.0f;
  b.rgba[4 * 6 + 1] += 0.5f / 255.0f;  // below the 8-bit threshold
  const ImageError e = compare_images(b, a);
  EXPECT_NEAR(e.max_abs, 2.0 / 255.0, 1e-7);
  EXPECT_DOUBLE_EQ(e.share_over_1_255, 1.0 / 128.0);
  EXPECT_NEAR(e.rmse, std::sqrt((std::pow(2.0 / 255, 2) + std::pow(0.5 / 255, 2)) / (16 * 8 * 4)), 1e-8);
  EXPECT_LT(e.ssim, 1.0);
  EXPECT_GT(e.ssim, 0.99);
}

TEST(ErrorMetrics, SsimPunishesLostStructureMoreThanAnEqualUniformShift) {
  const Image a = gradient(32, 32);
  Image shifted = a, flat = a;
  double mean = 0.0;
  for (float v : a.rgba) mean += v;
  mean /= double(a.rgba.size());
  for (size_t i = 0; i < a.rgba.size(); ++i) {
    shifted.rgba[i] = a.rgba[i] + 0.05f;
    flat.rgba[i] = float(mean);
  }
  EXPECT_GT(structural_similarity(shifted, a), structural_similarity(flat, a));
}

TEST(ErrorMetrics, NanMakesTheErrorInfiniteAndSizesMustMatch) {
  const Image a = gradient(4, 4);
  Image b = a;
  b.rgba[3] = std::nanf("");
  const ImageError e = compare_images(b, a);
  EXPECT_TRUE(std::isinf(e.max_abs));
  EXPECT_EQ(e.share_over_1_255, 1.0);
  EXPECT_THROW(compare_images(gradient(4, 5), a), std::invalid_argument);
}

}  // namespace
}  // namespace oit

#include "harness/output/heatmap.h"

namespace oit {
namespace {

TEST(Heatmap, ErrorsSitOnOneAbsoluteLogScaleNotOnTheirOwnMaximum) {
  // Off by 0.25 in one pixel, or by 6e-8: each map scaled to its own
  // maximum made both pixels the top colour. On the shared scale 6e-8 is
  // the bottom colour (<= 1e-4) and 0.25 sits at (log10 0.25 + 4) / 4.
  Image a = gradient(4, 4), b = a, c = a;
  b.rgba[4 * 5 + 2] += 0.25f;
  c.rgba[4 * 5 + 2] += 6e-8f;
  const Image big = error_heatmap(b, a), tiny = error_heatmap(c, a);
  float expected[3], bottom[3];
  viridis((std::log10(0.25f) + 4.0f) / 4.0f, expected);
  viridis(0.0f, bottom);
  for (int ch = 0; ch < 3; ++ch) {
    EXPECT_NEAR(big.at(1, 1, ch), srgb_decode(expected[ch]), 1e-3f) << ch;  // pixel 5 = (1, 1)
    EXPECT_NEAR(big.at(0, 0, ch), srgb_decode(bottom[ch]), 1e-6f) << ch;
    EXPECT_NEAR(tiny.at(1, 1, ch), srgb_decode(bottom[ch]), 1e-6f) << ch;
  }
}

}  // namespace
}  // namespace oit
