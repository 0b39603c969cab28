// Image error against the reference: max, RMSE, PSNR, SSIM, and the share
// of pixels with a visible (8-bit) difference.
#include <gtest/gtest.h>

#include <cmath>

#include "harness/core/error_metrics.h"

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

#include "harness/core/heatmap.h"

namespace oit {
namespace {

TEST(Heatmap, ZeroIsBlueTheMaximumIsRedAndTheErrorMapFindsThePixel) {
  const Image map = heatmap({0.0f, 0.5f, 1.0f}, 3, 1);
  EXPECT_GT(map.at(0, 0, 2), 0.4f);  // blue
  EXPECT_EQ(map.at(0, 0, 0), 0.0f);
  EXPECT_GT(map.at(2, 0, 0), 0.4f);  // red
  EXPECT_EQ(map.at(2, 0, 2), 0.0f);
  EXPECT_EQ(map.at(1, 0, 1), 1.0f);  // green in the middle
  Image a = gradient(4, 4), b = a;
  b.rgba[4 * 5 + 2] += 0.25f;
  const Image errors = error_heatmap(b, a);
  EXPECT_GT(errors.at(1, 1, 0), 0.4f);  // pixel 5 = (1, 1) is the worst: red
  EXPECT_EQ(errors.at(0, 0, 0), 0.0f);
}

}  // namespace
}  // namespace oit
