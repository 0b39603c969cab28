// What oitbench's image files hold (issue 21): PNGs display-ready (sRGB of
// the composite, opaque), PFMs linear; --images names distinct per run and
// never over an earlier file; error heatmaps on one absolute log scale with
// a colour bar that is the same in every file; LDR-FLIP on cases whose
// value is known in closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "harness/app/sweep.h"
#include "harness/core/error_metrics.h"
#include "harness/core/flip.h"
#include "harness/core/heatmap.h"
#include "harness/core/image.h"
#include "tests/oitbench_process.h"
#include "tests/png_file.h"

namespace oit {
namespace {

const std::string kOut = std::string(OIT_BINARY_DIR) + "/test_output/image_output";

std::string fresh_dir(const std::string& name) {
  const std::string dir = kOut + "/" + name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

using test::Png;
using test::load_png;

std::string contents_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

Image uniform(int width, int height, float r, float g, float b) {
  Image image{width, height, {}};
  for (int i = 0; i < width * height; ++i) image.rgba.insert(image.rgba.end(), {r, g, b, 1.0f});
  return image;
}

// ---- PNG and PFM encoding ----

TEST(ImageOutput, PngIsTheSrgbEncodedCompositeAndOpaque) {
  // Linear values and their sRGB bytes, worked out by hand from IEC 61966-2-1:
  // 0.5 -> 187.516 -> 188; 0.0015654 (linear segment) -> 5.157 -> 5; 0.2 -> 123.555 -> 124.
  const Image image{2, 1, {0.5f, 0.0015654f, 1.0f, 0.25f, 0.2f, 0.2f, 0.2f, 0.0f}};
  const std::string path = fresh_dir("encoding") + "/two.png";
  write_image(image, path);
  const Png png = load_png(path);
  ASSERT_EQ(png.width, 2);
  const int expected[2][4] = {{188, 5, 255, 255}, {124, 124, 124, 255}};
  for (int x = 0; x < 2; ++x)
    for (int c = 0; c < 4; ++c) EXPECT_EQ(png.at(x, 0, c), expected[x][c]) << x << " " << c;
  // raw: the values as bytes, alpha kept (window screenshots).
  write_image(image, path, PngEncoding::raw);
  const Png raw = load_png(path);
  EXPECT_EQ(raw.at(0, 0, 0), 128);
  EXPECT_EQ(raw.at(0, 0, 3), 64);
  EXPECT_EQ(raw.at(1, 0, 3), 0);
}

TEST(ImageOutput, RenderPngIsSrgbOfTheLinearCompositeThePfmHolds) {
  // quads at alpha 0.3 over a coloured background: coverage < 1 nowhere
  // hides in the PNG any more; its RGB is the PFM's (already composited
  // over the background) sRGB-encoded, exactly.
  const std::string dir = fresh_dir("render");
  const std::string args = "render --technique reference --scene quads --scene-set layers=2 --size 8x8 "
                           "--background 0.2,0.3,0.4 --out " + dir;
  ASSERT_EQ(test::run_oitbench(dir, args + "/q.png").exit_code, 0);
  ASSERT_EQ(test::run_oitbench(dir, args + "/q.pfm").exit_code, 0);
  const Png png = load_png(dir + "/q.png");
  const Image pfm = read_pfm(dir + "/q.pfm");
  ASSERT_EQ(png.width, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(png.at(x, 7 - y, c), int(std::lround(srgb_encode(pfm.at(x, y, c)) * 255.0f))) << x << "," << y;
      EXPECT_EQ(png.at(x, 7 - y, 3), 255);
    }
  // Linear and display differ: the PFM is not what the PNG shows.
  EXPECT_NE(png.at(0, 0, 0), int(std::lround(pfm.at(0, 7, 0) * 255.0f)));
}

TEST(ImageOutput, PngLinearKeepsTheValuesAndTheCoverage) {
  // --png linear: the linear values as bytes and alpha = coverage (PNGs as
  // they were before display became the default); a bad value names itself.
  const std::string dir = fresh_dir("png_linear");
  const std::string args = "render --technique reference --scene quads --scene-set layers=2 --size 8x8 --out " + dir;
  ASSERT_EQ(test::run_oitbench(dir, args + "/q.pfm").exit_code, 0);
  ASSERT_EQ(test::run_oitbench(dir, args + "/q.png --png linear").exit_code, 0);
  const Png png = load_png(dir + "/q.png");
  const Image pfm = read_pfm(dir + "/q.pfm");
  ASSERT_EQ(png.width, 8);
  bool partial_coverage = false;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(png.at(x, 7 - y, c), int(std::lround(pfm.at(x, y, c) * 255.0f)));
      partial_coverage |= png.at(x, 7 - y, 3) > 0 && png.at(x, 7 - y, 3) < 255;
    }
  EXPECT_TRUE(partial_coverage) << "two quads at alpha 0.3 cover 51%";
  const test::Outcome bad = test::run_oitbench(dir, args + "/bad.png --png srgb");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("srgb"), std::string::npos) << bad.output;
  EXPECT_THROW(parse_png_encoding("srgb"), std::invalid_argument);
}

TEST(ImageOutput, WriteNewImageNeverReplacesAFile) {
  const std::string dir = fresh_dir("new_image");
  const Image black = uniform(2, 2, 0.0f, 0.0f, 0.0f), white = uniform(2, 2, 1.0f, 1.0f, 1.0f);
  EXPECT_EQ(write_new_image(black, dir + "/a.png"), dir + "/a.png");
  const std::string first = contents_of(dir + "/a.png");
  EXPECT_EQ(write_new_image(white, dir + "/a.png"), dir + "/a_2.png");
  EXPECT_EQ(write_new_image(white, dir + "/a.png"), dir + "/a_3.png");
  EXPECT_EQ(contents_of(dir + "/a.png"), first);
  EXPECT_EQ(load_png(dir + "/a_3.png").at(0, 0, 0), 255);
  // No temporary file is left beside them.
  size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) files += entry.is_regular_file();
  EXPECT_EQ(files, 3u);
}

// ---- file names of a sweep ----

TEST(ImageOutput, RunLabelsOfASweepAreDistinctAndNameSceneParametersSizeAndCamera) {
  SweepOptions options;
  options.techniques = {"unsorted", "weighted_blended", "kbuffer"};
  options.scenes = {"quads", "spheres"};
  options.scene_sets = {"alpha=0.3,0.6"};
  options.sizes = {"24x16"};
  const std::vector<RunSpec> runs = expand_sweep(options, builtin_techniques());
  ASSERT_EQ(runs.size(), 12u);
  std::set<std::string> labels;
  for (const RunSpec& spec : runs) {
    RunResult r;
    r.spec = spec;
    const std::string label = run_label(r);
    labels.insert(label);
    EXPECT_NE(label.find("_" + spec.scene + "_alpha-" + spec.scene_params.at("alpha") + "_24x16"), std::string::npos)
        << label;
  }
  EXPECT_EQ(labels.size(), 12u);
  RunResult r;
  r.spec.technique = "kbuffer";
  r.spec.params = {{"k", "4"}};
  r.spec.scene = "/data/models/bunny.glb";
  r.spec.camera = "random:4:7@2";
  r.spec.scene_rect = false;
  EXPECT_EQ(run_label(r), "kbuffer_k-4_bunny.glb_256x256_camera-random-4-7-2_scene-rect-off");
}

TEST(ImageOutput, BenchImagesOfATwelveRunSweepAreTwelveFilesAndARepeatAddsTwelveMore) {
  const std::string dir = fresh_dir("sweep");
  const std::string command = "bench --technique unsorted --technique weighted_blended --technique reference "
                              "--scene quads --scene spheres --scene-set alpha=0.3,0.6 --size 24x16 --frames 1 "
                              "--warmup 0 --csv " + dir + "/runs.csv --images " + dir + "/images";
  const test::Outcome first = test::run_oitbench(dir, command);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  std::set<std::string> images, errors;
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/images")) {
    const std::string name = entry.path().filename().string();
    (name.find("_error") != std::string::npos ? errors : images).insert(name);
  }
  ASSERT_EQ(images.size(), 12u);
  for (const std::string& scene : {"quads", "spheres"})
    for (const std::string& alpha : {"0.3", "0.6"})
      for (const std::string& technique : {"unsorted", "weighted_blended", "reference"})
        EXPECT_EQ(images.count(technique + "_" + scene + "_alpha-" + alpha + "_24x16.png"), 1u)
            << technique << " " << scene << " " << alpha;
  // weighted_blended is approximate everywhere: one error map per run of it.
  EXPECT_GE(errors.size(), 4u);
  const std::string kept = contents_of(dir + "/images/unsorted_quads_alpha-0.3_24x16.png");
  const test::Outcome again = test::run_oitbench(dir, command);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(contents_of(dir + "/images/unsorted_quads_alpha-0.3_24x16.png"), kept);
  EXPECT_TRUE(std::filesystem::exists(dir + "/images/unsorted_quads_alpha-0.3_24x16_2.png"));
  EXPECT_NE(again.output.find("images: " + dir + "/images/unsorted_quads_alpha-0.3_24x16_2.png"), std::string::npos)
      << again.output;
  // Every error map carries the same colour bar, whatever its errors.
  std::string bar;
  for (const std::string& name : errors) {
    const Png png = load_png(dir + "/images/" + name);
    ASSERT_EQ(png.height, 16 + kColourBarHeight) << name;
    const std::string strip(png.rgba.begin() + ptrdiff_t(16) * png.width * 4, png.rgba.end());
    if (bar.empty()) bar = strip;
    EXPECT_EQ(strip, bar) << name;
  }
}

// ---- heatmaps ----

TEST(ImageOutput, HeatmapPngHoldsTheViridisTableBytes) {
  // viridis at 0, 1/2 and 1 is #440154, #21918c, #fde725; <= 1e-4 is the bottom.
  const std::vector<float> values = {0.0f, 1e-5f, 1e-2f, 1.0f, std::nanf("")};
  const std::string path = fresh_dir("viridis") + "/map.png";
  write_image(heatmap(values, 5, 1, error_scale()), path);
  const Png png = load_png(path);
  const int expected[5][3] = {{0x44, 0x01, 0x54}, {0x44, 0x01, 0x54}, {0x21, 0x91, 0x8c}, {0xfd, 0xe7, 0x25}, {0, 0, 0}};
  for (int x = 0; x < 5; ++x)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(png.at(x, 0, c), expected[x][c]) << x << " " << c;
}

TEST(ImageOutput, ColourBarIsTheSameForEveryMapOnOneScaleAndShowsTheScale) {
  const Image reference = uniform(64, 8, 0.5f, 0.5f, 0.5f);
  Image tiny = reference, large = reference;
  tiny.rgba[0] += 6e-8f;
  large.rgba[0] += 0.09f;
  const Image a = with_colour_bar(error_heatmap(tiny, reference), error_scale());
  const Image b = with_colour_bar(error_heatmap(large, reference), error_scale());
  ASSERT_EQ(a.width, kColourBarMinWidth);
  ASSERT_EQ(a.height, 8 + kColourBarHeight);
  const size_t strip = size_t(kColourBarMinWidth) * kColourBarHeight * 4;
  EXPECT_TRUE(std::equal(a.rgba.begin(), a.rgba.begin() + ptrdiff_t(strip), b.rgba.begin()));
  // 6e-8 is not 0.09's colour any more (each map scaled to its own maximum
  // made both the top colour).
  EXPECT_NE(a.at(0, kColourBarHeight, 1), b.at(0, kColourBarHeight, 1));
  // The bar's ticks are the decades 1e-4 .. 1, labelled as printed.
  const std::vector<float> ticks = error_scale().ticks();
  ASSERT_EQ(ticks.size(), 5u);
  std::vector<std::string> labels;
  for (float t : ticks) labels.push_back(error_scale().tick_label(t));
  EXPECT_EQ(labels, (std::vector<std::string>{"1e-4", "1e-3", "0.01", "0.1", "1"}));
}

// ---- FLIP ----

TEST(Flip, IdenticalImagesAreZero) {
  Image a = uniform(32, 24, 0.0f, 0.0f, 0.0f);
  for (size_t i = 0; i < a.rgba.size(); ++i) a.rgba[i] = float((i * 37) % 101) / 100.0f;
  EXPECT_EQ(mean_flip(a, a), 0.0);
}

TEST(Flip, UniformFieldsTakeTheirClosedFormColourValue) {
  // Uniform images: the filters leave them unchanged, no features, so FLIP
  // is the remapped Hunt-adjusted HyAB distance of the two colours.
  // Green vs blue is the normalising pair: exactly 1.
  EXPECT_NEAR(mean_flip(uniform(24, 24, 0, 1, 0), uniform(24, 24, 0, 0, 1)), 1.0, 1e-6);
  // Black vs white: HyAB 100, cmax = 203.29^0.7 = 41.2755;
  // 0.95 + 0.05 (100^0.7 - 0.4 cmax) / (0.6 cmax) = 0.967381.
  EXPECT_NEAR(mean_flip(uniform(24, 24, 0, 0, 0), uniform(24, 24, 1, 1, 1)), 0.967381, 1e-5);
  // Below the knee (pc cmax) the map is linear: grey 0.5 vs 0.25 (linear):
  // L* 76.0693 vs 57.0754, (18.9939^0.7) 0.95 / (0.4 cmax) = 0.451856.
  EXPECT_NEAR(mean_flip(uniform(24, 24, 0.5f, 0.5f, 0.5f), uniform(24, 24, 0.25f, 0.25f, 0.25f)), 0.451856, 1e-5);
}

TEST(Flip, ADisplacedEdgeErrsOnlyWithinTheFiltersReachAndIsSymmetric) {
  // A white half moved by one column: the CSF filters reach 10 pixels at
  // 67 pixels per degree, so FLIP is exactly 0 beyond that (the far tails
  // vanish in the clamp to [0, 1] a few pixels sooner), high at the step.
  Image a = uniform(64, 4, 0, 0, 0), b = a;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) {
        a.rgba[(size_t(y) * 64 + size_t(x)) * 4 + size_t(c)] = x >= 32 ? 1.0f : 0.0f;
        b.rgba[(size_t(y) * 64 + size_t(x)) * 4 + size_t(c)] = x >= 33 ? 1.0f : 0.0f;
      }
  const std::vector<float> map = flip_map(b, a);
  for (int x = 0; x < 64; ++x) {
    if (x < 22 || x > 42) EXPECT_EQ(map[size_t(x)], 0.0f) << x;
    if (x >= 26 && x <= 38) EXPECT_GT(map[size_t(x)], 1e-4f) << x;
  }
  // The colour filters blur the step; the feature term lifts the error at it.
  EXPECT_GT(*std::max_element(map.begin() + 29, map.begin() + 34), 0.5f);
  EXPECT_EQ(flip_map(a, b), map);
  EXPECT_THROW(flip_map(a, uniform(8, 8, 0, 0, 0)), std::invalid_argument);
}

TEST(Flip, IsAnErrorColumnBesidePsnrAndSsim) {
  const Image a = uniform(16, 16, 0, 1, 0), b = uniform(16, 16, 0, 0, 1);
  EXPECT_NEAR(compare_images(a, b).flip, 1.0, 1e-6);
  EXPECT_EQ(compare_images(a, a).flip, 0.0);
  const auto& columns = csv_columns();
  const auto ssim = std::find(columns.begin(), columns.end(), "ssim");
  ASSERT_NE(ssim, columns.end());
  EXPECT_EQ(*(ssim + 1), "flip");
}

}  // namespace
}  // namespace oit
