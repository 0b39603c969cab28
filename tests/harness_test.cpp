// The harness contract seen through Harness::run: registry, parameter errors,
// skipped and error rows, both clocks, the stage vocabulary, and the shader
// loader's #include / #define / error reporting.
#include <gtest/gtest.h>

#include <cstdlib>
#include <map>

#include "harness/gl/shader_program.h"
#include "tests/gl_fixture.h"
#include "scenes/scene_library.h"

namespace oit {
namespace {

RunSpec small_run(const std::string& technique, const RawParams& params = {}) {
  return test::one_frame(technique, params, "quads", {{"layers", "4"}}, 16);
}

// tests/CMakeLists.txt gives every discovered test both variables (through
// `cmake -E env`): the reference cache off, Mesa's shader cache in the build.
TEST(TestEnvironment, CtestGivesBothVariables) {
  const char* reference_cache = std::getenv("OIT_REFERENCE_CACHE");
  const char* shader_cache = std::getenv("MESA_SHADER_CACHE_DIR");
  ASSERT_NE(reference_cache, nullptr) << "run through ctest";
  EXPECT_STREQ(reference_cache, "off");
  ASSERT_NE(shader_cache, nullptr) << "run through ctest";
  EXPECT_EQ(std::string(shader_cache), std::string(OIT_BINARY_DIR) + "/mesa_shader_cache");
}

TEST(Registry, ListsTheFoundationTechniquesAndTheReference) {
  const auto& registry = builtin_techniques();
  EXPECT_NO_THROW(registry.get("unsorted"));
  EXPECT_NO_THROW(registry.get("reference"));
  EXPECT_EQ(registry.reference().id, "reference");
  EXPECT_EQ(registry.get("unsorted").exactness, Exactness::approximate);
  for (const auto& t : registry.all()) {
    EXPECT_FALSE(t.stages.empty()) << t.id;
    for (const auto& stage : t.stages) EXPECT_TRUE(is_stage_name(stage)) << t.id << " declares stage '" << stage << "'";
  }
}

TEST(Registry, StagesAreDistinctSnakeCaseNamesATechniqueChooses) {
  TechniqueRegistry registry;
  auto descriptor = [](std::vector<std::string> stages) {
    TechniqueDescriptor d;
    d.id = "staged";
    d.stages = std::move(stages);
    d.create = [](const ParamSet&) -> std::unique_ptr<Technique> { return nullptr; };
    return d;
  };
  EXPECT_NO_THROW(registry.add(descriptor({"clear", "build_histogram", "compose"})));  // a new word is fine
  for (const std::vector<std::string>& bad : {std::vector<std::string>{"Fill"}, {"fill", "fill"}, {"total"}, {""}}) {
    TechniqueRegistry fresh;
    EXPECT_THROW(fresh.add(descriptor(bad)), std::logic_error) << (bad.empty() ? "" : bad.front());
  }
  EXPECT_TRUE(is_stage_name("build_histogram2"));
  EXPECT_FALSE(is_stage_name("2nd"));
  EXPECT_FALSE(is_stage_name("has space"));
}

TEST(Registry, UnknownTechniqueNamesTheRegisteredOnes) {
  const RunResult r = test::harness().run(small_run("no_such_technique"));
  EXPECT_EQ(r.status, RunStatus::error);
  EXPECT_NE(r.message.find("no_such_technique"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("reference"), std::string::npos) << r.message;
}

TEST(Harness, BadParameterIsAnErrorRowNamingKeyAndRange) {
  const RunResult r = test::harness().run(small_run("reference", {{"initial_nodes_per_pixel", "0"}}));
  EXPECT_EQ(r.status, RunStatus::error);
  EXPECT_NE(r.message.find("initial_nodes_per_pixel"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("[1, 1024]"), std::string::npos) << r.message;
  const RunResult unknown = test::harness().run(small_run("unsorted", {{"k", "4"}}));
  EXPECT_EQ(unknown.status, RunStatus::error);
  EXPECT_NE(unknown.message.find("'k'"), std::string::npos) << unknown.message;
}

TEST(Harness, BadSceneParameterAndSizeAreErrorRows) {
  RunSpec spec = small_run("unsorted");
  spec.scene_params = {{"layers", "0"}};
  RunResult r = test::harness().run(spec);
  EXPECT_EQ(r.status, RunStatus::error);
  EXPECT_NE(r.message.find("layers"), std::string::npos) << r.message;
  spec = small_run("unsorted");
  spec.width = 0;
  r = test::harness().run(spec);
  EXPECT_EQ(r.status, RunStatus::error);
  EXPECT_NE(r.message.find("0x16"), std::string::npos) << r.message;
}

// A technique registered only in this test: it draws nothing, and may throw
// or use a stage name outside the vocabulary on request.
class Probe final : public Technique {
 public:
  explicit Probe(std::string behaviour) : behaviour_(std::move(behaviour)) {}
  void resize(int, int) override {}
  void render(const Frame& frame) override {
    if (behaviour_ == "throw") throw std::runtime_error("probe failed on purpose");
    auto s = frame.clock.stage(behaviour_ == "bad_stage" ? "bogus" : "fill");
  }
  TechniqueCounters counters() const override { return {}; }

 private:
  std::string behaviour_;
};

TechniqueRegistry probe_registry() {
  TechniqueRegistry registry;
  registry.add(builtin_techniques().reference());
  TechniqueDescriptor d;
  d.id = "probe";
  d.display_name = "probe";
  d.params = {ParamSpec::choice("behaviour", "ok", {"ok", "throw", "bad_stage"}, "what render does")};
  d.stages = {"fill"};
  d.needs.multiple_objects = true;
  d.create = [](const ParamSet& p) { return std::make_unique<Probe>(p.choice("behaviour")); };
  registry.add(std::move(d));
  return registry;
}

TEST(Harness, UnsupportedRunIsSkippedWithTheReasonAndTheSweepGoesOn) {
  const TechniqueRegistry registry = probe_registry();
  Harness harness(test::gl_context(), registry);
  RunSpec spec = small_run("probe");
  spec.scene_params = {{"layers", "4"}, {"objects", "1"}};
  const RunResult skipped = harness.run(spec);
  EXPECT_EQ(skipped.status, RunStatus::skipped);
  EXPECT_NE(skipped.message.find("single object"), std::string::npos) << skipped.message;
  spec.scene_params = {{"layers", "4"}, {"objects", "4"}};
  EXPECT_EQ(harness.run(spec).status, RunStatus::ok);
}

// The reference sorts by uvec2 keys (its README: a uint64 key sorted wrongly
// on NVIDIA's driver), so it needs no 64-bit integers; a technique that
// declares them is skipped with the reason on a device without them.
TEST(Harness, DeviceWithoutInt64RunsTheReferenceAndSkipsWhatDeclaresInt64) {
  DeviceProfile weak = test::gl_context().device();
  weak.int64 = false;
  const auto& reference = builtin_techniques().reference();
  EXPECT_EQ(supports(reference, ParamSet(reference.params, {}, "t"), weak, SceneFacts{2, 1, true}), "");
  TechniqueDescriptor needs_int64 = reference;
  needs_int64.needs.int64 = true;
  const std::string reason = supports(needs_int64, ParamSet(needs_int64.params, {}, "t"), weak, SceneFacts{2, 1, true});
  EXPECT_NE(reason.find("64-bit integers"), std::string::npos) << reason;
}

TEST(Harness, FailingTechniqueIsAnErrorRowAndTheNextRunWorks) {
  const TechniqueRegistry registry = probe_registry();
  Harness harness(test::gl_context(), registry);
  RunSpec spec = small_run("probe", {{"behaviour", "throw"}});
  spec.scene_params = {{"layers", "4"}, {"objects", "4"}};
  RunResult r = harness.run(spec);
  EXPECT_EQ(r.status, RunStatus::error);
  EXPECT_NE(r.message.find("probe failed on purpose"), std::string::npos) << r.message;

  spec.params = {{"behaviour", "bad_stage"}};
  r = harness.run(spec);
  EXPECT_EQ(r.status, RunStatus::error);
  EXPECT_NE(r.message.find("bogus"), std::string::npos) << r.message;

  spec.params = {};
  EXPECT_EQ(harness.run(spec).status, RunStatus::ok);
}

// The paper plots against triangles and vertices (carnecky2013 Fig. 15,
// pastyrik2016 Fig. 9) read them from every run's extra counters.
TEST(Harness, EveryRunRecordsTheScenesTrianglesAndVertices) {
  const RunSpec spec = small_run("unsorted");
  const RunResult r = test::harness().run(spec);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  const Scene scene = load_scene(spec.scene, spec.scene_params);
  std::map<std::string, double> extra;
  for (const Figure& figure : r.counters.extra) extra[figure.name] = figure.value;
  EXPECT_EQ(extra["scene_triangles"], double(scene.triangle_count()));
  EXPECT_EQ(extra["scene_vertices"], double(scene.vertices.size()));
  EXPECT_GT(extra["scene_triangles"], 0.0);
}

TEST(Harness, BothClocksGiveEveryStageTwiceAndACalibrationFigure) {
  RunSpec spec = small_run("reference");
  spec.frames = 3;
  spec.clock = ClockKind::both;
  const RunResult r = test::harness().run(spec);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  for (const char* stage : {"clear", "fill", "compose", "total"}) {
    for (const char* clock : {"gl", "wall"}) {
      const StageResult* s = r.stage(stage, clock);
      ASSERT_NE(s, nullptr) << stage << " " << clock;
      EXPECT_EQ(s->samples_ms.size(), 3u);
      EXPECT_GT(s->summary.median, 0.0) << stage << " " << clock;
    }
  }
  ASSERT_TRUE(r.clock_disagreement.has_value());
  EXPECT_GE(*r.clock_disagreement, 0.0);
  // Stages nest inside total on the wall clock, frame by frame.
  for (size_t i = 0; i < 3; ++i) {
    double parts = 0.0;
    for (const char* stage : {"clear", "fill", "compose"}) parts += r.stage(stage, "wall")->samples_ms[i];
    EXPECT_LE(parts, r.stage("total", "wall")->samples_ms[i]) << "frame " << i;
  }
}

TEST(ShaderLoader, CompileErrorNamesTheIncludedFileAndLine) {
  test::gl_context();
  try {
    build_fullscreen_program("tests/shaders/broken.frag");
    FAIL() << "a broken shader compiled";
  } catch (const ShaderError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("tests/shaders/broken_include.glsl:3"), std::string::npos) << message;
    EXPECT_NE(message.find("tests/shaders/broken.frag"), std::string::npos) << message;
  }
  EXPECT_THROW(build_fullscreen_program("tests/shaders/missing.frag"), ShaderError);
}

TEST(ShaderLoader, DefinesAreInjectedAndIncludesResolved) {
  test::gl_context();
  const Program program = build_fullscreen_program("tests/shaders/defined_value.frag", {{"VALUE", "0.625"}});
  const glm::vec4 texel = test::drawn_texel(program);
  EXPECT_EQ(texel.r, 0.625f);
  EXPECT_EQ(texel.g, 8.0f);  // OIT_FIRST_TECHNIQUE_UNIFORM from shaders/bindings.h
}

}  // namespace
}  // namespace oit
