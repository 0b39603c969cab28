// bucketed_kbuffer transfer functions from files (color_transfer_file,
// opacity_transfer_file): text and PNG read into the same texels as the
// built-ins, the same images rendered, and every malformed file refused
// with a message naming the file, the line and the value.
#include <gtest/gtest.h>
#include <stb_image_write.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "algorithms/bucketed_kbuffer/transfer_files.h"
#include "algorithms/bucketed_kbuffer/transfer_functions.h"
#include "harness/output/error_metrics.h"
#include "tests/error_of.h"
#include "tests/gl_fixture.h"

namespace oit {
namespace {

namespace fs = std::filesystem;

// One directory per test process, removed when the process ends.
const fs::path& scratch() {
  struct Directory {
    fs::path path = fs::temp_directory_path() / ("oit_bkb_transfer_" + std::to_string(getpid()));
    Directory() { fs::create_directories(path); }
    ~Directory() {
      std::error_code ignored;
      fs::remove_all(path, ignored);
    }
  };
  static const Directory dir;
  return dir.path;
}

std::string write_text(const std::string& name, const std::string& text) {
  const fs::path path = scratch() / name;
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

// 8-bit PNG of `channels` channels, rows top first.
std::string write_png(const std::string& name, int width, int height, int channels, const std::vector<uint8_t>& data) {
  const fs::path path = scratch() / name;
  EXPECT_TRUE(stbi_write_png(path.c_str(), width, height, channels, data.data(), width * channels));
  return path.string();
}

std::string format(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);  // reads back to the same float
  return text;
}

// The built-in opacity at every texel of the 64x64 grid, as a text grid.
std::string opacity_grid_text(bkb::OpacityTransfer function) {
  const std::vector<float> texels = bkb::opacity_texels(function);
  std::string text = "# rows: depth 0 .. 1, columns: |kappa| 0 .. 1\n";
  for (int y = 0; y < bkb::kOpacityTransferSize; ++y) {
    for (int x = 0; x < bkb::kOpacityTransferSize; ++x)
      text += (x ? " " : "") + format(texels[size_t(y * bkb::kOpacityTransferSize + x)]);
    text += "\n";
  }
  return text;
}

double largest_difference(const std::vector<float>& a, const std::vector<float>& b) {
  EXPECT_EQ(a.size(), b.size());
  double largest = 0.0;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) largest = std::max(largest, double(std::abs(a[i] - b[i])));
  return largest;
}

using test::error_of;

RunResult run(const RawParams& params, RunStatus expected = RunStatus::ok) {
  RunResult r = test::harness().run(test::one_frame("bucketed_kbuffer", params, "quads", {{"layers", "8"}}, 48));
  EXPECT_EQ(r.status, expected) << r.message;
  return r;
}

TEST(BkbTransferFiles, TextFilesReproduceTheBuiltInTexels) {
  // mean_curvature_shading is 1 - 0.5 kappa and curved_bright 0.5 + |kappa|:
  // three keyed points each; the interpolation differs from the built-ins'
  // float arithmetic by rounding only.
  const std::string shading = write_text("shading.txt", "# kappa multiplier\n-1 1.5\n0 1\n1 0.5\n");
  EXPECT_LE(largest_difference(bkb::load_color_transfer_file(shading),
                               bkb::color_texels(bkb::ColorTransfer::mean_curvature_shading)),
            1e-6);
  const std::string bright = write_text("bright.txt", "-1, 1.5, 1.5, 1.5\n0, 0.5, 0.5, 0.5  # flat\n1, 1.5, 1.5, 1.5\n");
  EXPECT_LE(largest_difference(bkb::load_color_transfer_file(bright),
                               bkb::color_texels(bkb::ColorTransfer::curved_bright)),
            1e-6);
  // One value per texel, evenly spaced: every texel exactly as written.
  std::string per_texel;
  const std::vector<float> builtin = bkb::color_texels(bkb::ColorTransfer::curved_bright);
  for (int i = 0; i < bkb::kColorTransferSize; ++i) per_texel += format(builtin[size_t(i) * 4]) + "\n";
  EXPECT_EQ(bkb::load_color_transfer_file(write_text("per_texel.txt", per_texel)), builtin);
  for (auto function : {bkb::OpacityTransfer::front_focus, bkb::OpacityTransfer::depth_range}) {
    const std::string grid = write_text("grid.txt", opacity_grid_text(function));
    EXPECT_EQ(bkb::load_opacity_transfer_file(grid), bkb::opacity_texels(function));
  }
}

TEST(BkbTransferFiles, ColourFormsAndResampling) {
  // Evenly spaced "r g b": 0 at kappa -1, 1 at +1 in red, the reverse in green.
  const std::vector<float> ramp = bkb::load_color_transfer_file(write_text("ramp.txt", "0 1 2\n1 0 2\n"));
  // "kappa m" held constant beyond the first and last kappa.
  const std::vector<float> step = bkb::load_color_transfer_file(write_text("step.txt", "-0.5 0\n0.5 1\n"));
  for (int i = 0; i < bkb::kColorTransferSize; ++i) {
    const double u = double(i) / (bkb::kColorTransferSize - 1), kappa = 2.0 * u - 1.0;
    const size_t t = size_t(i) * 4;
    EXPECT_NEAR(ramp[t + 0], u, 1e-6) << i;
    EXPECT_NEAR(ramp[t + 1], 1.0 - u, 1e-6) << i;
    EXPECT_EQ(ramp[t + 2], 2.0f) << i;
    EXPECT_EQ(ramp[t + 3], 1.0f) << i;
    const double expected = std::clamp(kappa + 0.5, 0.0, 1.0);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(step[t + size_t(c)], expected, 1e-6) << i;
  }
  // A single value: a constant.
  for (float v : bkb::load_color_transfer_file(write_text("one.txt", "0.75\n"))) EXPECT_TRUE(v == 0.75f || v == 1.0f);
}

TEST(BkbTransferFiles, PngGradientsAreReadTexelForTexel) {
  // Colour: 256 wide, so pixel i is texel i; the second row must be ignored.
  std::vector<uint8_t> rgb;
  for (int row = 0; row < 2; ++row)
    for (int i = 0; i < 256; ++i) rgb.insert(rgb.end(), {uint8_t(row ? 0 : i), uint8_t(row ? 0 : 255 - i), 128});
  const std::vector<float> color = bkb::load_color_transfer_file(write_png("gradient.png", 256, 2, 3, rgb));
  ASSERT_EQ(color.size(), size_t(bkb::kColorTransferSize) * 4);
  for (int i = 0; i < 256; ++i) {
    EXPECT_EQ(color[size_t(i) * 4 + 0], float(i / 255.0)) << i;
    EXPECT_EQ(color[size_t(i) * 4 + 1], float((255 - i) / 255.0)) << i;
    EXPECT_EQ(color[size_t(i) * 4 + 2], float(128 / 255.0)) << i;
  }
  // Opacity: 3 x 2 greyscale, top row = depth 0 (0, 51, 255 over |kappa|),
  // bottom row = depth 1 (all 255); bilinear in between.
  const std::vector<float> opacity =
      bkb::load_opacity_transfer_file(write_png("opacity.png", 3, 2, 1, {0, 51, 255, 255, 255, 255}));
  ASSERT_EQ(opacity.size(), size_t(bkb::kOpacityTransferSize) * bkb::kOpacityTransferSize);
  const double last = bkb::kOpacityTransferSize - 1;
  for (int y = 0; y < bkb::kOpacityTransferSize; ++y)
    for (int x = 0; x < bkb::kOpacityTransferSize; ++x) {
      const double u = x / last, depth = y / last;
      const double front = u <= 0.5 ? 0.2 * (2.0 * u) : 0.2 + 0.8 * (2.0 * u - 1.0);
      const double expected = (1.0 - depth) * front + depth * 1.0;
      EXPECT_NEAR(opacity[size_t(y * bkb::kOpacityTransferSize + x)], expected, 1e-6) << x << "," << y;
    }
}

TEST(BkbTransferFiles, FilesReproducingTheBuiltInsRenderTheSameImage) {
  // Same opacity texels bit for bit; colour texels within float rounding,
  // which can move a stylized RGBA8 colour channel by one step (1/255) but
  // no alpha. The composite weights sum to at most 1, so the image may
  // differ by at most 1/255 (+ float rounding of the compose).
  const std::string color = write_text("shading.txt", "-1 1.5\n0 1\n1 0.5\n");
  const std::string opacity = write_text("front.txt", opacity_grid_text(bkb::OpacityTransfer::front_focus));
  const RunResult builtin = run({{"k", "8"}});
  const RunResult files = run({{"k", "8"},
                               {"color_transfer", "identity"},
                               {"opacity_transfer", "identity"},
                               {"color_transfer_file", color},
                               {"opacity_transfer_file", opacity}});
  EXPECT_LE(compare_images(files.image, builtin.image).max_abs, 1.0 / 255.0 + 1e-5);
  // The stylization is on in both (the image is not the reference).
  ASSERT_TRUE(builtin.error.has_value());
  EXPECT_GT(builtin.error->max_abs, 0.05);
}

TEST(BkbTransferFiles, IdentityColourFileGivesTheIdentityImage) {
  // A multiplier of exactly 1 leaves every stored RGBA8 colour as it is.
  const std::string one = write_text("identity.txt", "# the shaded colour unchanged\n1\n");
  const RawParams unstylized = {{"k", "8"}, {"color_transfer", "identity"}, {"opacity_transfer", "identity"}};
  RawParams with_file = unstylized;
  with_file["color_transfer_file"] = one;
  const RunResult identity = run(unstylized), file = run(with_file);
  EXPECT_EQ(compare_images(file.image, identity.image).max_abs, 0.0);
  ASSERT_TRUE(file.error.has_value() && identity.error.has_value());
  EXPECT_EQ(file.error->max_abs, identity.error->max_abs);  // the reference, up to RGBA8 packing
  // The file overrides a non-identity choice too.
  with_file["color_transfer"] = "curved_bright";
  EXPECT_EQ(compare_images(run(with_file).image, identity.image).max_abs, 0.0);
}

TEST(BkbTransferFiles, MalformedTextNamesFileLineAndValue) {
  struct Case {
    bool opacity;
    const char* name;
    std::string text;
    std::vector<const char*> expected;  // parts of the message
  };
  const Case cases[] = {
      {false, "words.txt", "1.0\n# fine\nabc 1\n", {"line 3", "'abc'", "not a number"}},
      {false, "nan.txt", "0.5\nnan\n", {"line 2", "'nan'", "not a finite"}},
      {false, "inf.txt", "inf\n", {"line 1", "'inf'"}},
      {false, "negative.txt", "1\n-0.5\n", {"line 2", "-0.5"}},
      {false, "huge.txt", "1e300\n", {"line 1", "1e+300"}},
      {false, "mixed.txt", "1\n1 1 1\n", {"line 2", "3 values", "same form"}},
      {false, "five.txt", "1 2 3 4 5\n", {"line 1", "5 values"}},
      {false, "order.txt", "-1 1\n0.5 1\n0.5 2\n", {"line 3", "0.5", "does not increase"}},
      {false, "range.txt", "-2 1\n1 1\n", {"line 1", "kappa -2", "[-1, 1]"}},
      {false, "empty.txt", "", {"no values"}},
      {false, "comments.txt", "# nothing\n\n   \n", {"no values"}},
      {true, "ragged.txt", "0 0.5 1\n0 0.5\n", {"line 2", "2 values", "rectangular"}},
      {true, "above.txt", "0 0.5\n0.25 1.5\n", {"line 2", "column 2", "1.5", "[0, 1]"}},
      {true, "below.txt", "-0.1\n", {"line 1", "-0.1"}},
      {true, "nan_grid.txt", "0 NaN\n", {"line 1", "'NaN'"}},
      {true, "binary.txt", std::string("\x01\x02\xff", 3), {"line 1", "not a number"}},
      {true, "empty_grid.txt", "\n", {"no values"}},
  };
  for (const Case& c : cases) {
    const std::string path = write_text(c.name, c.text);
    const std::string message = error_of([&] {
      c.opacity ? bkb::load_opacity_transfer_file(path) : bkb::load_color_transfer_file(path);
    });
    ASSERT_FALSE(message.empty()) << c.name << " was accepted";
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(c.opacity ? "opacity_transfer_file" : "color_transfer_file"), std::string::npos)
        << message;
    for (const char* part : c.expected) EXPECT_NE(message.find(part), std::string::npos) << c.name << ": " << message;
  }
}

TEST(BkbTransferFiles, BadImagesAndMissingFilesAreClearErrors) {
  // A PNG whose header says 0 x 1 pixels (stb_image does not check CRCs).
  const std::string header("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\0\0\0\0\0\0\x01\x08\x02\0\0\0\0\0\0\0", 33);
  const std::string zero = write_text("zero.png", header + std::string("\0\0\0\0IEND\xae\x42\x60\x82", 12));
  const std::string truncated = write_text("truncated.png", header.substr(0, 20));
  for (const std::string& path : {zero, truncated}) {
    for (bool opacity : {false, true}) {
      const std::string message = error_of([&] {
        opacity ? bkb::load_opacity_transfer_file(path) : bkb::load_color_transfer_file(path);
      });
      EXPECT_NE(message.find(path), std::string::npos) << message;
      EXPECT_NE(message.find("PNG"), std::string::npos) << message;
    }
  }
  const std::string missing = (scratch() / "missing.txt").string();
  EXPECT_NE(error_of([&] { bkb::load_color_transfer_file(missing); }).find("cannot be opened"), std::string::npos);
  // Through the harness: the parameter is refused before anything is read,
  // a malformed file when the technique is built; both are error rows.
  for (const auto& [key, path, part] :
       {std::tuple{"color_transfer_file", missing, std::string("does not exist")},
        std::tuple{"opacity_transfer_file", scratch().string(), std::string("is a directory")},
        std::tuple{"opacity_transfer_file", write_text("bad.txt", "0.5\n2\n"), std::string("line 2")}}) {
    const RunResult r = run({{key, path}}, RunStatus::error);
    EXPECT_NE(r.message.find(key), std::string::npos) << r.message;
    EXPECT_NE(r.message.find(path), std::string::npos) << r.message;
    EXPECT_NE(r.message.find(part), std::string::npos) << r.message;
  }
}

TEST(BkbTransferFiles, CommittedExamplesLoad) {
  const fs::path examples = fs::path(OIT_SOURCE_DIR) / "algorithms/bucketed_kbuffer/examples";
  const std::vector<float> warm_cool = bkb::load_color_transfer_file((examples / "color_warm_cool.txt").string());
  // kappa -1 (convex): warm, red above blue; kappa +1 (concave): cool.
  EXPECT_GT(warm_cool[0], warm_cool[2]);
  EXPECT_LT(warm_cool[warm_cool.size() - 4], warm_cool[warm_cool.size() - 2]);
  // The 9 x 9 example samples front_focus; linear interpolation between
  // its samples stays within 0.05 of the built-in.
  const std::vector<float> opacity = bkb::load_opacity_transfer_file((examples / "opacity_front_focus_9x9.txt").string());
  EXPECT_LE(largest_difference(opacity, bkb::opacity_texels(bkb::OpacityTransfer::front_focus)), 0.05);
}

}  // namespace
}  // namespace oit
