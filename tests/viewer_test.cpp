// The viewer's parts that need no window: the orbit camera (an untouched
// camera is its preset, bit for bit), the sweep-file line (what it appends
// is a command `oitbench bench` accepts and runs) and the live technique
// (on the headless context: the harness's image, stage timings, refusal of
// invalid parameters with the schema's message).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/app/viewer/live_technique.h"
#include "harness/app/viewer/orbit_camera.h"
#include "harness/app/viewer/param_editor.h"
#include "harness/app/viewer/sweep_line.h"
#include "tests/gl_fixture.h"
#include "scenes/scene.h"
#include "scenes/scene_library.h"

namespace oit {
namespace {

Camera preset() {
  return frame_bounding_sphere(BoundingSphere{glm::vec3(1.0f, 2.0f, 3.0f), 2.0f}, glm::vec3(1.0f, 0.5f, 2.0f));
}

TEST(ViewerOrbitCamera, UntouchedCameraIsThePresetExactly) {
  const Camera p = preset();
  const OrbitCamera orbit(p, BoundingSphere{glm::vec3(1.0f, 2.0f, 3.0f), 2.0f});
  EXPECT_FALSE(orbit.moved());
  const Camera c = orbit.camera();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_EQ(c.view[i][j], p.view[i][j]);
  EXPECT_EQ(c.znear, p.znear);
  EXPECT_EQ(c.zfar, p.zfar);
}

TEST(ViewerOrbitCamera, OrbitKeepsTheTargetAndDistanceZoomMovesCloserResetRestores) {
  const BoundingSphere sphere{glm::vec3(1.0f, 2.0f, 3.0f), 2.0f};
  OrbitCamera orbit(preset(), sphere);
  const float d0 = glm::length(orbit.eye() - sphere.center);
  orbit.orbit(40.0f, -25.0f, 256.0f);
  EXPECT_TRUE(orbit.moved());
  EXPECT_NEAR(glm::length(orbit.eye() - sphere.center), d0, 1e-4f * d0);
  // The target stays in the middle of the image.
  const Camera c = orbit.camera();
  const glm::vec4 centre = c.projection(1.0f) * c.view * glm::vec4(sphere.center, 1.0f);
  EXPECT_NEAR(centre.x / centre.w, 0.0f, 1e-4f);
  EXPECT_NEAR(centre.y / centre.w, 0.0f, 1e-4f);
  orbit.zoom(2.0f);
  EXPECT_LT(orbit.distance(), d0);
  orbit.pan(10.0f, 0.0f, 256.0f);
  orbit.reset();
  EXPECT_FALSE(orbit.moved());
  EXPECT_EQ(orbit.camera().view, preset().view);
}

TEST(ViewerSweepLine, QuotesWhatTheShellWouldSplit) {
  ViewConfig c;
  c.technique = "kbuffer";
  c.params = {{"k", "8"}, {"tail", "blend"}};
  c.scene = "/tmp/my model's dir/a b.obj";
  c.width = 64;
  c.height = 32;
  c.camera = "random:4:7@2";
  EXPECT_EQ(bench_command_line(c, "out.csv"),
            "oitbench bench --technique kbuffer --set k=8 --set tail=blend --scene '/tmp/my model'\\''s dir/a b.obj' "
            "--size 64x32 --camera random:4:7@2 --background 0,0,0 --csv out.csv");
}

TEST(ViewerSweepLine, SceneRectangleOffIsOnTheLine) {
  ViewConfig c;
  c.technique = "unsorted";
  c.scene = "quads";
  c.width = c.height = 8;
  EXPECT_EQ(bench_command_line(c, "o.csv").find("--scene-rect"), std::string::npos);  // on is the default
  c.scene_rect = false;
  EXPECT_NE(bench_command_line(c, "o.csv").find(" --scene-rect off "), std::string::npos);
}

TEST(ViewerSweepLine, RealParametersReadBackExactly) {
  for (double v : {0.1, 1.0 / 3.0, 2.5e-7, 100.0}) EXPECT_EQ(std::strtod(real_text(v).c_str(), nullptr), v);
}

TEST(ViewerSweepLine, AppendedLineRunsAsABenchCommand) {
  const std::string dir = std::string(OIT_BINARY_DIR) + "/test_output/viewer";
  std::filesystem::create_directories(dir);
  const std::string sweep = dir + "/sweep.txt", csv = dir + "/sweep.csv";
  std::filesystem::remove(sweep);
  std::filesystem::remove(csv);
  ViewConfig c;
  c.technique = "kbuffer";
  c.params = {{"k", "4"}};
  c.scene = "quads";
  c.scene_params = {{"layers", "8"}};
  c.width = c.height = 32;
  append_to_sweep_file(sweep, bench_command_line(c, csv), "a comment line");
  append_to_sweep_file(sweep, bench_command_line(c, csv));
  std::ifstream in(sweep);
  std::string comment, line, second;
  std::getline(in, comment);
  std::getline(in, line);
  std::getline(in, second);
  EXPECT_EQ(comment, "# a comment line");
  EXPECT_EQ(line, second);
  ASSERT_EQ(line.rfind("oitbench bench ", 0), 0u);
  // Run it with the built binary (a few frames: the line is about the
  // configuration, not the frame count).
  const std::string command = std::string(OIT_BINARY_DIR) + "/harness/oitbench" + line.substr(8) +
                              " --frames 1 --warmup 0 > " + dir + "/bench.log 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  std::ifstream rows(csv);
  std::stringstream text;
  text << rows.rdbuf();
  EXPECT_NE(text.str().find("kbuffer"), std::string::npos);
  EXPECT_NE(text.str().find("k=4"), std::string::npos);
}

struct LiveQuads {
  GlContext& context = test::gl_context();  // first: the scene uploads into it
  Scene scene = load_scene("quads", {{"layers", "8"}});
  SceneGpu gpu{scene};
  SceneFacts facts{scene.triangle_count(), scene.object_count, true};
};

TEST(ViewerLiveTechnique, RendersTheHarnessImageWithStageTimings) {
  LiveQuads quads;
  LiveTechnique live(builtin_techniques(), quads.context.device(), ClockKind::wall);
  ASSERT_EQ(live.configure("kbuffer", {{"k", "2"}}, quads.facts, quads.gpu.shading(), 48, 32), "");
  const Camera& camera = quads.scene.camera;
  for (int i = 0; i < 2; ++i) live.render(quads.gpu, camera.view, camera.projection(48.0f / 32.0f), glm::vec3(0.0f));
  const Image image = live.read_image();
  const RunResult run = test::render_once("kbuffer", {{"k", "2"}}, "quads", {{"layers", "8"}}, 48, 32);
  ASSERT_EQ(image.rgba.size(), run.image.rgba.size());
  EXPECT_EQ(image.rgba, run.image.rgba);
  bool has_total = false;
  for (const auto& t : live.timings()) has_total |= t.stage == "total" && t.summary.median > 0.0;
  EXPECT_TRUE(has_total);
  EXPECT_GT(live.counters().fragments_stored, 0u);
  EXPECT_EQ(live.canonical_params(), "k=2 tail=drop slot_layout=full auto_k_memory_mb=1024");
}

// The table's medians are over frames actually timed: the first frame after
// configure (shader compilation, allocation) is warm-up and left out; until
// a window of kWindow frames is complete it covers the timed frames so far,
// then the last complete window; timed_frames() says how many.
TEST(ViewerLiveTechnique, TimingsLeaveOutTheWarmUpFrameAndCountTheTimedFrames) {
  LiveQuads quads;
  LiveTechnique live(builtin_techniques(), quads.context.device(), ClockKind::wall);
  ASSERT_EQ(live.configure("unsorted", {}, quads.facts, quads.gpu.shading(), 16, 16), "");
  const Camera& camera = quads.scene.camera;
  auto frames = [&](int n) {
    for (int i = 0; i < n; ++i) live.render(quads.gpu, camera.view, camera.projection(1.0f), glm::vec3(0.0f));
  };
  auto total_count = [&]() -> size_t {
    for (const auto& t : live.timings())
      if (t.stage == "total") return t.summary.count;
    return 0;
  };
  frames(1);
  EXPECT_TRUE(live.timings().empty());
  EXPECT_EQ(live.timed_frames(), 0);
  frames(2);  // --frames 3: two timed frames, the compile frame not among them
  EXPECT_EQ(live.timed_frames(), 2);
  EXPECT_EQ(total_count(), 2u);
  frames(LiveTechnique::kWindow - 2);
  EXPECT_EQ(live.timed_frames(), LiveTechnique::kWindow);
  EXPECT_EQ(total_count(), size_t(LiveTechnique::kWindow));
  frames(3);  // the next window is not complete: the last complete one stays
  EXPECT_EQ(live.timed_frames(), LiveTechnique::kWindow);
  EXPECT_EQ(total_count(), size_t(LiveTechnique::kWindow));
  ASSERT_EQ(live.configure("unsorted", {}, quads.facts, quads.gpu.shading(), 16, 16), "");
  EXPECT_EQ(live.timed_frames(), 0);
  EXPECT_TRUE(live.timings().empty());
}

TEST(ViewerLiveTechnique, InvalidParametersAreRefusedWithTheSchemaMessageAndTheOldOneKeepsRunning) {
  LiveQuads quads;
  LiveTechnique live(builtin_techniques(), quads.context.device(), ClockKind::wall);
  ASSERT_EQ(live.configure("kbuffer", {{"k", "4"}}, quads.facts, quads.gpu.shading(), 16, 16), "");
  const std::string message = live.configure("kbuffer", {{"k", "65"}}, quads.facts, quads.gpu.shading(), 16, 16);
  EXPECT_NE(message.find("'k'"), std::string::npos) << message;
  EXPECT_NE(message.find("[1, 64]"), std::string::npos) << message;
  EXPECT_NE(
      live.configure("kbuffer", {{"tail", "nope"}}, quads.facts, quads.gpu.shading(), 16, 16).find("{drop, blend}"),
      std::string::npos);
  EXPECT_NE(live.configure("no_such_technique", {}, quads.facts, quads.gpu.shading(), 16, 16), "");
  ASSERT_TRUE(live.ready());
  EXPECT_EQ(live.id(), "kbuffer");
  EXPECT_EQ(live.canonical_params(), "k=4 tail=drop slot_layout=full auto_k_memory_mb=1024");
  const Camera& camera = quads.scene.camera;
  live.render(quads.gpu, camera.view, camera.projection(1.0f), glm::vec3(0.0f));
}

// The viewer switches scenes under a running technique: one of the other
// shading gets the technique built again for it (gl/shader_program.h), so a
// lit scene after an unlit one is lit, and back again.
TEST(ViewerLiveTechnique, ASceneOfTheOtherShadingIsRenderedAsTheHarnessRendersIt) {
  LiveQuads quads;
  const Scene torus = load_scene("torus", {});
  const SceneGpu torus_gpu(torus);
  LiveTechnique live(builtin_techniques(), quads.context.device(), ClockKind::wall);
  ASSERT_EQ(live.configure("linked_list", {}, quads.facts, quads.gpu.shading(), 32, 32), "");
  auto expect_harness_image = [&](const Scene& scene, const SceneGpu& gpu, const RawParams& params) {
    SCOPED_TRACE(scene.name);
    live.render(gpu, scene.camera.view, scene.camera.projection(1.0f), glm::vec3(0.0f));
    const RunResult run = test::render_once("linked_list", {}, scene.name, params, 32, 32);
    EXPECT_EQ(live.read_image().rgba, run.image.rgba);
  };
  expect_harness_image(torus, torus_gpu, {});
  expect_harness_image(quads.scene, quads.gpu, {{"layers", "8"}});
}

// The viewer's "saved" line for the scene rectangle counts what the
// harness's pixels_outside_scene_rect counts for the same frame.
TEST(ViewerLiveTechnique, PixelsOutsideTheSceneRectangleAreTheHarnessCount) {
  GlContext& context = test::gl_context();
  const Scene scene = load_scene("torus", {});
  const SceneGpu gpu(scene);
  const SceneFacts facts{scene.triangle_count(), scene.object_count, true};
  LiveTechnique live(builtin_techniques(), context.device(), ClockKind::wall);
  ASSERT_EQ(live.configure("unsorted", {}, facts, gpu.shading(), 64, 48), "");
  const glm::mat4 view = scene.camera.view, projection = scene.camera.projection(64.0f / 48.0f);
  live.render(gpu, view, projection, glm::vec3(0.0f));
  const uint64_t expected = 64 * 48 - projected_scene_rect(gpu.bounding_box(), projection * view, 64, 48).pixels();
  ASSERT_GT(expected, 0u) << "the torus should leave pixels outside its rectangle";
  EXPECT_EQ(live.pixels_outside_scene_rect(), expected);
  const RunResult run = test::render_once("unsorted", {}, "torus", {}, 64, 48);
  double harness_count = -1.0;
  for (const auto& [name, value, combine] : run.counters.work_saved)
    if (name == kPixelsOutsideSceneRect) harness_count = value;
  EXPECT_EQ(harness_count, double(expected));
  live.set_scene_rect(false);
  live.render(gpu, view, projection, glm::vec3(0.0f));
  EXPECT_EQ(live.pixels_outside_scene_rect(), 0u);
}

}  // namespace
}  // namespace oit
