// `oitbench view` in a real window: run under `xvfb-run -a` (see
// CMakeLists.txt). Headless runs (--frames N --screenshot) must show, in the
// scene area (the top-left --size pixels of the screenshot), what the
// headless commands write for the same configuration: `render` for the
// technique and the reference, `stats --heatmap` for list lengths, and the
// harness's error_heatmap for the error view.
//
// Tolerance: every RGB channel within 1 of 255. Both sRGB-encode the
// linear image (harness/output/image.h, PngEncoding::display): the viewer in
// a compute shader (GLSL pow, conversion to 8 bits by GL), the PNG writer
// with std::pow and lround; the two may round differently at a half step.
// Alpha is not compared (both are opaque).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/output/heatmap.h"
#include "harness/output/image.h"
#include "harness/run/runner.h"
#include "tests/gl_fixture.h"
#include "tests/png_file.h"

namespace oit {
namespace {

const std::string kOitbench = std::string(OIT_BINARY_DIR) + "/harness/oitbench";
const std::string kOut = std::string(OIT_BINARY_DIR) + "/test_output/viewer_xvfb";
constexpr int kTolerance = 1;  // 8-bit levels

struct Outcome {
  int exit_code;
  std::string output;
};

Outcome run(const std::string& command_line) {
  std::filesystem::create_directories(kOut);
  const std::string log = kOut + "/last_command.txt";
  const int status = std::system((command_line + " > " + log + " 2>&1").c_str());
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

using test::Png;
using test::load_png;

// Largest RGB difference between the screenshot and `expected` over the
// columns [x0, x1) and rows [y0, y1) (rows from the top; y1 < 0: all of
// expected's rows).
int max_difference(const Png& screenshot, const Png& expected, int x0, int x1, int y0 = 0, int y1 = -1) {
  int worst = 0;
  for (int y = y0; y < (y1 < 0 ? expected.height : y1); ++y)
    for (int x = x0; x < x1; ++x)
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(screenshot.at(x, y, c) - expected.at(x, y, c)));
  return worst;
}

// Runs the viewer for a few frames and returns its screenshot.
Png view_screenshot(const std::string& arguments, const std::string& name) {
  const std::string shot = kOut + "/" + name + "_view.png";
  std::filesystem::remove(shot);
  const Outcome o = run(kOitbench + " view " + arguments + " --frames 3 --screenshot " + shot);
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("scene area x=0 y=0"), std::string::npos) << o.output;
  return load_png(shot);
}

Png render_png(const std::string& arguments, const std::string& name) {
  const std::string out = kOut + "/" + name + "_render.png";
  const Outcome o = run(kOitbench + " render " + arguments + " --out " + out);
  EXPECT_EQ(o.exit_code, 0) << o.output;
  return load_png(out);
}

void expect_scene_area_matches(const std::string& arguments, const std::string& name) {
  const Png expected = render_png(arguments, name);
  const Png shot = view_screenshot(arguments, name);
  ASSERT_GT(expected.width, 0);
  ASSERT_GE(shot.width, expected.width);
  ASSERT_GE(shot.height, expected.height);
  EXPECT_LE(max_difference(shot, expected, 0, expected.width), kTolerance) << name;
}

TEST(Viewer, ScreenshotSceneAreaMatchesRender) {
  expect_scene_area_matches("--technique linked_list --scene quads --size 128x96", "linked_list_quads");
}

// The viewer's defaults (quads, 512x512) with linked_list: 10.5M fragments,
// more than one 128 MiB storage block on llvmpipe, rendered in tiles.
TEST(Viewer, DefaultSizeLinkedListRendersInTiles) {
  expect_scene_area_matches("--technique linked_list --scene quads --size 512x512", "linked_list_512");
}

TEST(Viewer, ScreenshotMatchesRenderFromARandomViewpointWithParameters) {
  expect_scene_area_matches(
      "--technique kbuffer --set k=2 --scene spheres --size 96x96 --camera random:4:7@2 --background 0.2,0.3,0.4",
      "kbuffer_spheres_random");
}

TEST(Viewer, ReferenceDisplayMatchesRenderOfTheReference) {
  const std::string config = "--scene torus --size 96x80";
  const Png expected = render_png("--technique reference " + config, "reference_torus");
  const Png shot = view_screenshot("--technique unsorted --display reference " + config, "reference_torus");
  ASSERT_GT(expected.width, 0);
  EXPECT_LE(max_difference(shot, expected, 0, expected.width), kTolerance);
}

TEST(Viewer, ListLengthDisplayMatchesStatsHeatmap) {
  const std::string heatmap = kOut + "/list_length_stats.png";
  const Outcome o = run(kOitbench + " stats --scene spheres --size 96x96 --heatmap " + heatmap);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const Png shot = view_screenshot("--scene spheres --size 96x96 --display list_length", "list_length");
  const Png expected = load_png(heatmap);
  // The PNG has its colour bar below the map (and is at least 200 wide);
  // the viewer draws its bar in the panel: compare the 96x96 map.
  ASSERT_EQ(expected.height, 96 + kColourBarHeight);
  EXPECT_LE(max_difference(shot, expected, 0, 96, 0, 96), kTolerance);
}

TEST(Viewer, ErrorDisplayIsTheHarnessErrorHeatmap) {
  // The expected heatmap from the harness itself (RGBA, as the viewer
  // compares), on a headless context of this process.
  auto context = create_headless_context();
  Harness harness(*context, builtin_techniques());
  const RunSpec spec = test::one_frame("kbuffer", {{"k", "2"}}, "quads", {{"layers", "8"}}, 64);
  const RunResult result = harness.run(spec);
  ASSERT_EQ(result.status, RunStatus::ok) << result.message;
  ASSERT_GT(result.error->max_abs, 0.0) << "k=2 on 8 layers should be approximate";
  const Image& reference = harness.reference_image("quads", spec.scene_params, 64, 64, glm::vec3(0.0f));
  const std::string expected_path = kOut + "/error_expected.png";
  write_image(error_heatmap(result.image, reference), expected_path);
  const Png shot = view_screenshot(
      "--technique kbuffer --set k=2 --display error --scene quads --scene-set layers=8 --size 64x64", "error");
  const Png expected = load_png(expected_path);
  ASSERT_GT(expected.width, 0);
  EXPECT_LE(max_difference(shot, expected, 0, expected.width), kTolerance);
}

// --display diagnostic: the heatmap (over the field's own range) of the
// technique's diagnostic image of the same frame, computed here on the
// headless context.
void expect_diagnostic_display(const std::string& technique, const RawParams& params, const std::string& set,
                               const std::string& name, const std::string& diagnostic) {
  const std::vector<DiagnosticImage> images =
      test::diagnostic_images_once(technique, params, "spheres", {{"count", "1"}}, 64, 64);
  const DiagnosticImage* field = nullptr;
  for (const DiagnosticImage& d : images)
    if (diagnostic.empty() ? field == nullptr : d.name == diagnostic) field = &d;
  ASSERT_NE(field, nullptr) << technique << " offers no '" << diagnostic << "'";
  const std::string expected_path = kOut + "/" + name + "_expected.png";
  write_image(heatmap_range(field->values, field->width, field->height, field->low, field->high), expected_path);
  const Png shot = view_screenshot("--technique " + technique + set + " --display diagnostic" +
                                       (diagnostic.empty() ? "" : " --diagnostic " + diagnostic) +
                                       " --scene spheres --scene-set count=1 --size 64x64",
                                   name);
  const Png expected = load_png(expected_path);
  ASSERT_GT(expected.width, 0);
  ASSERT_GE(shot.width, expected.width);
  EXPECT_LE(max_difference(shot, expected, 0, expected.width), kTolerance) << name;
}

TEST(Viewer, DiagnosticDisplayIsTheHeatmapOfTheTechniquesDiagnosticImage) {
  expect_diagnostic_display("illustration_buffer", {}, "", "diagnostic_silhouette", "silhouette");
  expect_diagnostic_display("illustration_buffer", {}, "", "diagnostic_neighbor_count", "neighbor_count");
  // No --diagnostic: the technique's first (bucketed_kbuffer: kappa).
  expect_diagnostic_display("bucketed_kbuffer", {{"curvature_scale", "0.2"}}, " --set curvature_scale=0.2",
                            "diagnostic_kappa", "");
}

TEST(Viewer, DiagnosticDisplayOfATechniqueWithoutDiagnosticsIsAMessageNotAFailure) {
  // kbuffer offers none: the scene area is black, the run still succeeds.
  const Png shot = view_screenshot("--technique kbuffer --display diagnostic --scene quads --size 32x32",
                                   "diagnostic_none");
  ASSERT_GE(shot.width, 32);
  int brightest = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      for (int c = 0; c < 3; ++c) brightest = std::max(brightest, shot.at(x, y, c));
  EXPECT_EQ(brightest, 0);
}

TEST(Viewer, SplitShowsTechniqueAOnTheLeftAndBOnTheRight) {
  const std::string config = " --scene spheres --size 128x96";
  const Png a = render_png("--technique linked_list" + config, "split_a");
  const Png b = render_png("--technique unsorted" + config, "split_b");
  const Png shot =
      view_screenshot("--technique linked_list --compare unsorted --show split" + config, "split");
  ASSERT_GT(a.width, 0);
  // The split line (x = 64) and the technique labels (top rows) are drawn
  // over the image; compare around them.
  EXPECT_LE(max_difference(shot, a, 0, 62, 20), kTolerance);
  EXPECT_LE(max_difference(shot, b, 66, 128, 20), kTolerance);
  EXPECT_GT(max_difference(shot, b, 0, 62, 20), kTolerance) << "A and B should differ on spheres";
}

// Split mode splits the error and diagnostic displays like the image:
// A's heatmap left of the split line, B's right of it (labels and the line
// are drawn over the top rows and the middle columns; compare around them).
TEST(Viewer, SplitErrorDisplayShowsEachTechniquesErrorHeatmapOnItsSide) {
  // Spheres: the two approximate techniques err in different places
  // (kbuffer where lists exceed k, unsorted where submission order is wrong).
  Harness& harness = test::harness();
  const Image& reference = harness.reference_image("spheres", {}, 64, 64, glm::vec3(0.0f));
  const RunResult a = test::render_once("kbuffer", {{"k", "2"}}, "spheres", {}, 64, 64);
  const RunResult b = test::render_once("unsorted", {}, "spheres", {}, 64, 64);
  write_image(error_heatmap(a.image, reference), kOut + "/split_error_a.png");
  write_image(error_heatmap(b.image, reference), kOut + "/split_error_b.png");
  const Png shot = view_screenshot(
      "--technique kbuffer --set k=2 --compare unsorted --show split --display error --scene spheres --size 64x64",
      "split_error");
  const Png expected_a = load_png(kOut + "/split_error_a.png"), expected_b = load_png(kOut + "/split_error_b.png");
  ASSERT_GT(expected_a.width, 0);
  EXPECT_LE(max_difference(shot, expected_a, 0, 30, 20), kTolerance);
  EXPECT_LE(max_difference(shot, expected_b, 34, 64, 20), kTolerance);
  EXPECT_GT(max_difference(expected_a, expected_b, 0, 30, 20), kTolerance) << "the two error maps should differ";
  EXPECT_GT(max_difference(expected_a, expected_b, 34, 64, 20), kTolerance) << "the two error maps should differ";
}

TEST(Viewer, SplitDiagnosticDisplayShowsEachTechniquesFieldOnItsSide) {
  const RawParams sphere{{"count", "1"}};
  const auto a = test::diagnostic_images_once("illustration_buffer", {}, "spheres", sphere, 64, 64);
  const auto b = test::diagnostic_images_once("bucketed_kbuffer", {}, "spheres", sphere, 64, 64);
  const DiagnosticImage* field_a = test::find_diagnostic(a, "neighbor_count");
  const DiagnosticImage* field_b = test::find_diagnostic(b, "neighbor_count");
  ASSERT_TRUE(field_a && field_b);
  // Both halves on one scale: the union of the two fields' natural ranges.
  const float low = std::min(field_a->low, field_b->low), high = std::max(field_a->high, field_b->high);
  for (const auto& [field, name] : {std::pair{field_a, "a"}, std::pair{field_b, "b"}})
    write_image(heatmap_range(field->values, field->width, field->height, low, high),
                kOut + "/split_diagnostic_" + name + ".png");
  const Png shot = view_screenshot("--technique illustration_buffer --compare bucketed_kbuffer --show split "
                                   "--display diagnostic --diagnostic neighbor_count --scene spheres "
                                   "--scene-set count=1 --size 64x64",
                                   "split_diagnostic");
  const Png expected_a = load_png(kOut + "/split_diagnostic_a.png");
  const Png expected_b = load_png(kOut + "/split_diagnostic_b.png");
  ASSERT_GT(expected_a.width, 0);
  EXPECT_LE(max_difference(shot, expected_a, 0, 30, 20), kTolerance);
  EXPECT_LE(max_difference(shot, expected_b, 34, 64, 20), kTolerance);
}

TEST(Viewer, WithoutADisplayExitsNonZeroWithAdvice) {
  const Outcome o = run("env -u DISPLAY -u WAYLAND_DISPLAY " + kOitbench + " view --frames 1");
  EXPECT_EQ(o.exit_code, 1) << o.output;  // an orderly error, not a crash (signal)
  EXPECT_NE(o.output.find("DISPLAY"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("oitbench render"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("xvfb-run"), std::string::npos) << o.output;
}

TEST(Viewer, InvalidParameterIsRefusedWithTheSchemaMessage) {
  const Outcome o = run(kOitbench + " view --technique kbuffer --set k=0 --size 32x32 --frames 1");
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find("'k'"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("[1, 64]"), std::string::npos) << o.output;
}

}  // namespace
}  // namespace oit
