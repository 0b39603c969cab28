// Issue 40, "mistakes that deserve a better answer", below the command line:
// the closest-name suggestion, how --set / --scene-set scopes and repeats
// expand, --baseline, sizes and colours, the progress line's clock and the
// text wrapping of long lines. The command line itself: tests/cli_test.cpp.
#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
#include <string>
#include <tuple>

#include "base/params.h"
#include "base/suggest.h"
#include "harness/app/bench_report.h"
#include "harness/app/sweep.h"
#include "harness/toolkit/technique.h"
#include "tests/error_of.h"

namespace oit {
namespace {

using test::error_of;

TEST(Suggest, ClosestNameTakesTyposAndPrefixesButNotStrangers) {
  const std::vector<std::string> techniques = {"kbuffer", "linked_list", "unsorted"};
  EXPECT_EQ(closest_name("linked_lsit", techniques), "linked_list");  // two letters swapped: one edit
  EXPECT_EQ(closest_name("kbufer", techniques), "kbuffer");
  EXPECT_EQ(closest_name("benchmark", {"list", "render", "bench", "pareto"}), "bench");  // a prefix
  EXPECT_EQ(closest_name("--frame", {"--frames", "--warmup", "--size"}), "--frames");
  EXPECT_EQ(closest_name("weighted", techniques), "");
  EXPECT_EQ(closest_name("kbuffer", techniques), "");  // the word itself is no suggestion
  EXPECT_EQ(did_you_mean("unsortd", techniques), "; did you mean unsorted?");
  EXPECT_EQ(did_you_mean("zzz", techniques), "");
}

TEST(Suggest, ParameterLookupsSuggestTheClosestKeyAndChoice) {
  const ParamSchema schema = {ParamSpec::integer("layers", 4, 1, 64, ""),
                              ParamSpec::choice("sort", "insertion", {"insertion", "merge"}, ""),
                              ParamSpec::real("alpha", 0.5, 0.0, 1.0, "")};
  EXPECT_NE(error_of([&] { ParamSet(schema, {{"layer", "3"}}, "scene 'quads'"); })
                .find("scene 'quads' has no parameter 'layer'; did you mean layers?"),
            std::string::npos);
  EXPECT_NE(error_of([&] { ParamSet(schema, {{"sort", "insertoin"}}, "t"); })
                .find("is not a valid choice; did you mean insertion?"),
            std::string::npos);
  // Numbers too large for their type are out of range, not "not a number".
  EXPECT_NE(error_of([&] { ParamSet(schema, {{"alpha", "1e400"}}, "t"); }).find("'1e400' is out of range"),
            std::string::npos);
  EXPECT_NE(error_of([&] { ParamSet(schema, {{"layers", "99999999999999999999"}}, "t"); }).find("is out of range"),
            std::string::npos);
  EXPECT_NE(error_of([&] { ParamSet(schema, {{"layers", "-3"}}, "t"); }).find("'-3' is out of range"),
            std::string::npos);
  EXPECT_NE(error_of([] { builtin_techniques().get("linked_lsit"); }).find("did you mean linked_list?"),
            std::string::npos);
}

SweepOptions sweep_of(std::vector<std::string> techniques, std::vector<std::string> scenes,
                      std::vector<std::string> sets, std::vector<std::string> scene_sets) {
  SweepOptions sweep;
  sweep.techniques = std::move(techniques);
  sweep.scenes = std::move(scenes);
  sweep.technique_sets = std::move(sets);
  sweep.scene_sets = std::move(scene_sets);
  sweep.sizes = {"8x8"};
  return sweep;
}

std::string sweep_error(const SweepOptions& sweep) {
  return error_of([&] { expand_sweep(sweep, builtin_techniques()); });
}

TEST(SweepScopes, ATechniqueScopeMustNameASelectedTechnique) {
  EXPECT_EQ(sweep_error(sweep_of({"kbuffer"}, {"quads"}, {"nosuch.k=4"}, {})),
            "--set nosuch.k=4: there is no technique 'nosuch'");
  EXPECT_EQ(sweep_error(sweep_of({"kbuffer"}, {"quads"}, {"kbufer.k=4"}, {})),
            "--set kbufer.k=4: there is no technique 'kbufer'; did you mean kbuffer?");
  EXPECT_EQ(sweep_error(sweep_of({"kbuffer"}, {"quads"}, {"linked_list.k=4"}, {})),
            "--set linked_list.k=4: linked_list is not among the selected techniques (kbuffer); add -t linked_list "
            "or leave this --set out");
  EXPECT_EQ(sweep_error(sweep_of({"kbuffer"}, {"quads"}, {"kbuffer.kk=4"}, {})),
            "--set kbuffer.kk=4: technique 'kbuffer' has no parameter 'kk'; did you mean k?");
  EXPECT_EQ(sweep_error(sweep_of({"kbuffer", "unsorted"}, {"quads"}, {"kk=4"}, {})),
            "--set kk=4: no selected technique has a parameter 'kk'; did you mean k?");
}

TEST(SweepScopes, AKeyGivenTwiceIsRefusedWithTheListToGive) {
  EXPECT_EQ(sweep_error(sweep_of({"kbuffer"}, {"quads"}, {"k=2", "k=3"}, {})),
            "--set k is given twice (k=2, k=3); give its values as one list: --set k=2,3");
  EXPECT_EQ(sweep_error(sweep_of({"kbuffer"}, {"quads"}, {"kbuffer.k=2", "kbuffer.k=3,4"}, {})),
            "--set kbuffer.k is given twice (kbuffer.k=2, kbuffer.k=3,4); give its values as one list: "
            "--set kbuffer.k=2,3,4");
  EXPECT_EQ(sweep_error(sweep_of({"unsorted"}, {"quads"}, {}, {"layers=2", "layers=3"})),
            "--scene-set layers is given twice (layers=2, layers=3); give its values as one list: "
            "--scene-set layers=2,3");
}

TEST(SweepScopes, AScopedKeyOverridesTheUnscopedOneForItsTechniqueOnly) {
  const auto runs = expand_sweep(sweep_of({"kbuffer", "hybrid_transparency"}, {"quads"}, {"k=2", "kbuffer.k=8"}, {}),
                                 builtin_techniques());
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].technique, "kbuffer");
  EXPECT_EQ(runs[0].params, (RawParams{{"k", "8"}}));
  EXPECT_EQ(runs[1].technique, "hybrid_transparency");
  EXPECT_EQ(runs[1].params, (RawParams{{"k", "2"}}));
}

TEST(SweepScopes, SceneSetsAreScopedAndApplyWhereTheKeyExists) {
  // Scoped to quads: torus runs with its own defaults.
  const auto scoped = expand_sweep(sweep_of({"unsorted"}, {"quads", "torus"}, {}, {"quads.layers=4"}),
                                   builtin_techniques());
  ASSERT_EQ(scoped.size(), 2u);
  EXPECT_EQ(scoped[0].scene_params, (RawParams{{"layers", "4"}}));
  EXPECT_EQ(scoped[1].scene, "torus");
  EXPECT_TRUE(scoped[1].scene_params.empty());
  // Unscoped: where the key exists, as --set does.
  const auto unscoped = expand_sweep(sweep_of({"unsorted"}, {"quads", "torus"}, {}, {"layers=4,8"}),
                                     builtin_techniques());
  ASSERT_EQ(unscoped.size(), 3u);
  EXPECT_EQ(unscoped[1].scene_params, (RawParams{{"layers", "8"}}));
  EXPECT_TRUE(unscoped[2].scene_params.empty());
  // A scene that is not selected, or a key no selected scene has: errors, never dropped.
  EXPECT_EQ(sweep_error(sweep_of({"unsorted"}, {"quads"}, {}, {"torus.layers=4"})),
            "--scene-set torus.layers=4: torus is not among the selected scenes (quads); add -s torus or leave "
            "this --scene-set out");
  EXPECT_EQ(sweep_error(sweep_of({"unsorted"}, {"quads", "torus"}, {}, {"layrs=4"})),
            "--scene-set layrs=4: no selected scene has a parameter 'layrs'; did you mean layers?");
  EXPECT_EQ(sweep_error(sweep_of({"unsorted"}, {"quads"}, {}, {"quadz.layers=4"})),
            "--scene-set quadz.layers=4: there is no scene 'quadz'; did you mean quads?");
}

TEST(SweepScopes, OneValueCommandsScopeAndRefuseRepeatsTheSameWay) {
  const TechniqueRegistry& registry = builtin_techniques();
  const std::vector<const TechniqueDescriptor*> both = {&registry.get("kbuffer"), &registry.get("unsorted")};
  const auto params = one_value_technique_params({"kbuffer.k=4"}, both, registry);
  ASSERT_EQ(params.size(), 2u);
  EXPECT_EQ(params[0], (RawParams{{"k", "4"}}));
  EXPECT_TRUE(params[1].empty());
  // A value is kept whole: one run takes one value (ParamSet names a list as no integer).
  EXPECT_EQ(one_value_technique_params({"k=2,3"}, {both[0]}, registry)[0], (RawParams{{"k", "2,3"}}));
  EXPECT_EQ(error_of([&] { one_value_technique_params({"k=2", "k=3"}, {both[0]}, registry); }),
            "--set k is given twice (k=2, k=3); give it once");
  EXPECT_EQ(error_of([&] { one_value_technique_params({"linked_list.max_per_pixel=4"}, {both[0]}, registry); }),
            "--set linked_list.max_per_pixel=4: linked_list is not among the selected techniques (kbuffer); add "
            "-t linked_list or leave this --set out");
  EXPECT_EQ(one_value_scene_params({"quads.layers=3"}, "quads"), (RawParams{{"layers", "3"}}));
  EXPECT_EQ(error_of([] { one_value_scene_params({"layer=3"}, "quads"); }),
            "--scene-set layer=3: scene 'quads' has no parameter 'layer'; did you mean layers?");
  EXPECT_NE(error_of([] { one_value_scene_params({}, "quadz"); }).find("unknown scene 'quadz'; did you mean quads?"),
            std::string::npos);
}

// A run's Repetition as one value gtest compares and prints: warm-up frames
// and ms, least frames, precision, frame and seconds caps.
std::tuple<int, double, int, double, int, double> repetition_of(const RunSpec& spec) {
  return {spec.warmup, spec.warmup_ms, spec.frames, spec.precision, spec.max_frames, spec.max_seconds};
}

// A sweep gives every run its Repetition: precision-driven by default (the
// device's warm-up time for a negative warmup_ms), or --frames N: exactly N
// timed frames, with no precision target and no cap left over.
TEST(SweepRepetition, EveryRunTakesTheSweepsRepetitionOrExactlyItsFrames) {
  SweepOptions sweep = sweep_of({"unsorted"}, {"quads"}, {}, {});
  sweep.auto_warmup_ms = 250.0;
  sweep.repetition.frames = 8;
  sweep.repetition.max_frames = 5;  // below the least frames: raised to them
  EXPECT_EQ(repetition_of(expand_sweep(sweep, builtin_techniques()).at(0)), std::tuple(1, 250.0, 8, 0.05, 8, 2.0));
  sweep.repetition.warmup_ms = 40.0;
  sweep.exact_frames = 3;
  EXPECT_EQ(repetition_of(expand_sweep(sweep, builtin_techniques()).at(0)), std::tuple(1, 40.0, 3, 0.0, 0, 0.0));
}

TEST(Baseline, MustBeASelectedTechniqueId) {
  const TechniqueRegistry& registry = builtin_techniques();
  EXPECT_NO_THROW(validate_baseline("unsorted", {"all"}, registry));
  EXPECT_NO_THROW(validate_baseline("kbuffer", {"unsorted", "kbuffer"}, registry));
  EXPECT_EQ(error_of([&] { validate_baseline("linked_lsit", {"all"}, registry); }),
            "--baseline 'linked_lsit' is not a technique id; did you mean linked_list?");
  EXPECT_EQ(error_of([&] { validate_baseline("linked_list:sort=insertion", {"all"}, registry); }),
            "--baseline 'linked_list:sort=insertion' is not a technique id; did you mean linked_list? (the ratios "
            "divide by a technique's runs, whatever their parameters)");
  EXPECT_EQ(error_of([&] { validate_baseline("linked_list", {"kbuffer"}, registry); }),
            "--baseline linked_list is not among the selected techniques (kbuffer); add -t linked_list or choose "
            "one of them");
}

TEST(SizesAndColours, SizeTakesEitherXAndSuggestsTheSquare) {
  int width = 0, height = 0;
  parse_size("256X128", width, height);
  EXPECT_EQ(width, 256);
  EXPECT_EQ(height, 128);
  EXPECT_EQ(error_of([&] { parse_size("256", width, height); }),
            "size '256' is not of the form WIDTHxHEIGHT; did you mean 256x256?");
  EXPECT_EQ(error_of([&] { parse_size("99999999999x2", width, height); }),
            "size '99999999999x2' is outside 1x1 .. 16384x16384");
}

TEST(SizesAndColours, BackgroundRefusesNegativeAndHugeChannels) {
  EXPECT_EQ(parse_background("0.5,0,1"), glm::vec3(0.5f, 0.0f, 1.0f));
  EXPECT_EQ(error_of([] { parse_background("-0.1,0,0"); }),
            "--background '-0.1,0,0': '-0.1' is negative: colours are linear, each channel >= 0");
  EXPECT_EQ(error_of([] { parse_background("0,1e400,0"); }), "--background '0,1e400,0': '1e400' is out of range");
  EXPECT_EQ(error_of([] { parse_background("0,x,0"); }), "--background '0,x,0': 'x' is not a finite number");
}

TEST(ClockWarning, GlTimerQueriesOnASoftwareDeviceAreWarnedAbout) {
  DeviceProfile software;
  software.renderer = "llvmpipe (LLVM 15.0.6, 256 bits)";
  software.software = true;
  EXPECT_NE(clock_warning("gl", software).find("warning: --clock gl on llvmpipe"), std::string::npos);
  EXPECT_NE(clock_warning("both", software).find("--clock both"), std::string::npos);
  EXPECT_EQ(clock_warning("wall", software), "");
  EXPECT_EQ(clock_warning("auto", software), "");
  DeviceProfile gpu;
  gpu.renderer = "NVIDIA H100";
  EXPECT_EQ(clock_warning("gl", gpu), "");
}

// bench's progress line is `run_one(spec) + progress.timing_text(i + 1)`,
// whose operands C++ may evaluate in either order (GCC: right first): the
// elapsed time must still be read after the run.
TEST(Progress, TimingIsReadAfterTheRunWhicheverOperandIsEvaluatedFirst) {
  auto now = std::chrono::steady_clock::time_point{};
  const Progress progress(3, [&now] { return now; });
  auto run = [&now] {
    now += std::chrono::seconds(544);  // a long run
    return std::string("ok");
  };
  const std::string line = run() + progress.timing_text(1);
  EXPECT_EQ(line, "ok [elapsed 9:04, ETA 18:08]");  // two runs left at 544 s each
  now += std::chrono::seconds(544);
  EXPECT_EQ(std::string(progress.timing_text(2)), " [elapsed 18:08, ETA 9:04]");
  EXPECT_EQ(std::string(progress.timing_text(3)), " [elapsed 18:08]");
}

TEST(WrapText, WrapsToTheWidthKeepingEachLinesIndentation) {
  EXPECT_EQ(wrap_text("aaa bbb ccc ddd", 9, 2), "aaa bbb\n  ccc ddd");
  EXPECT_EQ(wrap_text("    k default 16 integer", 14, 8), "    k default\n        16\n        integer");
  EXPECT_EQ(wrap_text("one\n  two three", 9, 4), "one\n  two\n    three");
  EXPECT_EQ(wrap_text("averyveryverylongword x", 5, 1), "averyveryverylongword\n x");
  for (const std::string& line : {std::string("a b c d e f g h i j k l m n o p q r s t u v w x y z")}) {
    const std::string wrapped = wrap_text(line, 10, 2);
    size_t start = 0;
    for (size_t end = wrapped.find('\n'); ; end = wrapped.find('\n', start)) {
      EXPECT_LE((end == std::string::npos ? wrapped.size() : end) - start, 10u) << wrapped;
      if (end == std::string::npos) break;
      start = end + 1;
    }
  }
}

}  // namespace
}  // namespace oit
