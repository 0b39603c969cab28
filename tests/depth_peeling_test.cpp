// Depth peeling, both tie breaks: exact against the reference (quads and
// lit spheres, in any submission order) with every fragment peeled and
// counted; the occlusion query early exit stops right after the last layer
// (d + 1 passes by submission, d + 2 by triangle id) and without it exactly
// max_passes run; a pass cap below the depth complexity leaves an error that
// shrinks strictly as the cap grows, with the un-peeled rest counted.
// Depth ties: tie_break=triangle_id peels them like the reference in every
// submission order (coplanar stress layers, tied quads); tie_break=submission
// peels them completely, in submission order. A camera whose near plane is
// at the eye fails loudly by submission (depth buffer) and renders exactly by
// triangle id (no depth buffer); out-of-range parameters are rejected naming
// the parameter.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "tests/gl_fixture.h"
#include "tests/peeling_checks.h"

namespace oit::test {
namespace {

// What each tie break costs: geometry passes beyond the depth complexity,
// passes a cap spends without peeling a layer (a cap of P peels P - it), memory.
const TieBreak kTieBreaks[] = {
    // The nearest-depth pass + one per layer + the pass that composites the
    // last; accumulation RGBA32F + 2 RGBA32UI states + RG32F reductions.
    {"triangle_id", 2, 2, kPixels * (16 + 2 * 16 + 8)},
    // One per layer + the pass that finds nothing; layer colour RGBA32F +
    // depth + two RG32UI keys + accumulation RGBA32F, + a 4-byte counter.
    {"submission", 1, 0, kPixels * (16 + 4 + 2 * 8 + 16) + 4},
};

// One geometry pass per layer.
uint64_t passes_for_depth(uint64_t depth) { return depth; }

const test::OneFrameOf spec_of{"depth_peeling"};

TEST(DepthPeeling, ExactOnThirtyTwoQuadLayers) {
  for (const TieBreak& tie : kTieBreaks)
    test::expect_exact_on_thirty_two_quads("depth_peeling", tie.name, 32u + tie.extra_passes, tie.bytes, kSize);
}

// Exact on the lit spheres in any submission order; early exit stops right
// after the last layer (d + extra passes), without it 13 run, a cap of 5 <
// d + extra holds; passes avoided on 32 layers and on uneven depth.
TEST(DepthPeeling, ExactOnLitSpheresAndEarlyExitStopsRightAfterTheLastLayer) {
  test::expect_every_tie_break_exact_and_stopping_early("depth_peeling", kTieBreaks, passes_for_depth, 13, 5, kSize);
}

TEST(DepthPeeling, PassCapLeavesAnErrorThatShrinksWithMorePasses) {
  for (const TieBreak& tie : kTieBreaks) {
    SCOPED_TRACE(tie.name);
    // The nearest layers are peeled; the rest is counted as dropped.
    test::expect_error_shrinking_with_the_pass_cap(
        "depth_peeling", tie.name, [&](uint64_t cap) { return cap - tie.passes_not_compositing; }, kSize);
    // The same cap without early exit gives the same image.
    const RunResult capped = run_ok(spec_of({{"tie_break", tie.name}, {"max_passes", "8"}}, "quads", kQuads32, kSize));
    const RunResult no_exit = run_ok(spec_of({{"tie_break", tie.name}, {"max_passes", "8"}, {"early_exit", "false"}},
                                             "quads", kQuads32, kSize));
    EXPECT_EQ(capped.image.rgba, no_exit.image.rgba);
    EXPECT_EQ(no_exit.counters.fragments_dropped, (24u + tie.passes_not_compositing) * kPixels);
  }
}

TEST(DepthPeeling, CoplanarStressLayersMatchTheReferenceInEverySubmissionOrder) {
  // One pass per fragment of the tie, + 2.
  test::expect_coplanar_ties_like_the_reference("depth_peeling", kSize, 10);
}

TEST(DepthPeeling, SubmissionTieBreakPeelsCoplanarLayersCompletelyInSubmissionOrder) {
  // One tied fragment peeled per pass, + the pass that finds nothing.
  test::expect_submission_ties_in_submission_order("depth_peeling", kSize, 9);
}

TEST(DepthPeeling, DepthTiesArePeeledCompletelyOnePerPass) {
  // One quad in front, then three coplanar quads of different colours whose
  // fragments tie exactly in depth (triangle ids ascend in this order).
  const std::string path = test::write_quads_gltf(
      "depth_peeling", "ties",
      {{-1.0f, {0.9f, 0.9f, 0.1f, 0.3f}}, {-2.0f, {0.9f, 0.1f, 0.1f, 0.5f}},
       {-2.0f, {0.1f, 0.9f, 0.1f, 0.5f}}, {-2.0f, {0.1f, 0.1f, 0.9f, 0.5f}}});
  constexpr int size = 16;
  constexpr uint64_t pixels = uint64_t(size) * size;
  for (const TieBreak& tie : kTieBreaks) {
    for (const std::string order : {"original", "reversed", "shuffled:3"}) {
      SCOPED_TRACE(tie.name + " " + order);
      const RunResult r = run_ok(spec_of({{"tie_break", tie.name}}, path, {}, size, order));
      EXPECT_EQ(r.max_depth_complexity, 4u);
      // Every tied fragment is peeled in a pass of its own; none is lost.
      EXPECT_EQ(r.counters.fragments_stored, 4u * pixels);
      EXPECT_EQ(r.counters.fragments_dropped, 0u);
      EXPECT_EQ(r.counters.passes, 4u + tie.extra_passes);
      if (tie.name == "triangle_id" || order == "original") {
        // By id, or submitted in id order: the reference's order.
        EXPECT_LT(r.error->max_abs, 1e-5);
      } else if (order == "reversed") {
        // By submission, reversed: the tie is peeled in reverse id order.
        EXPECT_GT(r.error->max_abs, 0.05);
      }
    }
  }
}

TEST(DepthPeeling, RefusesACameraWhoseNearPlaneIsAtTheEye) {
  // By submission, depths <= 0 cannot be ordered by the depth test; rather
  // than merging layers silently the run fails, naming the technique and the range.
  const std::string path = test::write_quads_gltf(
      "depth_peeling", "near_zero", {{-1.0f, {0.9f, 0.1f, 0.1f, 0.5f}}, {-2.0f, {0.1f, 0.1f, 0.9f, 0.5f}}}, 0.0);
  const RunResult r = test::harness().run(spec_of({{"tie_break", "submission"}}, path, {}, 8));
  EXPECT_EQ(r.status, RunStatus::error);
  EXPECT_NE(r.message.find("depth_peeling"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("near plane"), std::string::npos) << r.message;
  // By triangle id no depth buffer is involved: any view depth is compared exactly.
  const RunResult by_id = run_ok(spec_of({{"tie_break", "triangle_id"}}, path, {}, 8));
  EXPECT_LT(by_id.error->max_abs, 1e-5);
  EXPECT_EQ(by_id.counters.fragments_stored, 2u * 64u);
}

TEST(DepthPeeling, RejectsOutOfRangeParametersNamingThem) {
  test::expect_bad_parameters_rejected_by_name("depth_peeling");
}

}  // namespace
}  // namespace oit::test
