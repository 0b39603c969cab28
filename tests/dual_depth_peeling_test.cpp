// Dual depth peeling, both tie breaks: exact against the reference (quads,
// an odd number of layers whose middle layer is both the nearest and the
// farthest, lit spheres; in any submission order) with every fragment
// counted; N layers cost ceil(N/2) + 1 geometry passes by submission,
// ceil(N/2) + 2 by triangle id, with early exit and exactly max_passes
// without; a pass cap leaves the middle layers out with an error that shrinks
// strictly as the cap grows. Depth ties: tie_break=triangle_id composites
// them like the reference in every submission order (coplanar stress layers;
// ties at the front, the back and in the middle); tie_break=submission
// composites them all, in submission order. Out-of-range parameters are
// rejected by name.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "tests/gl_fixture.h"
#include "tests/peeling_checks.h"

namespace oit::test {
namespace {

// What each tie break costs: geometry passes beyond ceil(d / 2), passes a
// cap spends without compositing (layers composited = 2 * (cap - it)), memory.
const TieBreak kTieBreaks[] = {
    // The min-max pass + the pass that composites the last selection; front
    // and back RGBA32F + 2 RGBA32UI keys + 2 RG32F next depths + RGBA32F reductions.
    {"triangle_id", 2, 2, kPixels * (2 * 16 + 2 * 16 + 2 * 8 + 16)},
    // The min-max pass; two RG32F depth ranges + front and back RGBA32F, + a 4-byte counter.
    {"submission", 1, 1, kPixels * (2 * 8 + 2 * 16) + 4},
};

// Two layers per geometry pass, front and back.
uint64_t passes_for_depth(uint64_t depth) { return (depth + 1) / 2; }

const test::OneFrameOf spec_of{"dual_depth_peeling"};

TEST(DualDepthPeeling, ExactOnThirtyTwoQuadLayersInHalfThePasses) {
  for (const TieBreak& tie : kTieBreaks)  // 16 passes of 2 layers
    test::expect_exact_on_thirty_two_quads("dual_depth_peeling", tie.name, 16u + tie.extra_passes, tie.bytes, kSize);
}

TEST(DualDepthPeeling, OddLayerCountCompositesTheMiddleLayerOnce) {
  // With 7 layers the 4th selection finds one fragment, nearest and farthest
  // at once: it must go to the front or the back accumulation, not both.
  for (const TieBreak& tie : kTieBreaks) {
    SCOPED_TRACE(tie.name);
    const RunResult r = run_ok(spec_of({{"tie_break", tie.name}}, "quads", {{"layers", "7"}, {"alpha", "0.6"}}, kSize));
    EXPECT_LT(r.error->max_abs, 1e-5);
    EXPECT_EQ(r.counters.passes, 4u + tie.extra_passes);  // ceil(7 / 2) + ...
    EXPECT_EQ(r.counters.fragments_stored, 7u * kPixels);
    EXPECT_EQ(r.counters.fragments_dropped, 0u);
  }
}

// Exact on the lit spheres in any submission order; ceil(d/2) + extra
// passes with early exit, without it exactly max_passes (9), a cap of 3 <
// ceil(d/2) + extra holds; passes avoided on 32 layers and on uneven depth.
TEST(DualDepthPeeling, ExactOnLitSpheresAndWithoutEarlyExitRunsExactlyMaxPasses) {
  test::expect_every_tie_break_exact_and_stopping_early("dual_depth_peeling", kTieBreaks, passes_for_depth, 9, 3,
                                                        kSize);
}

TEST(DualDepthPeeling, PassCapLeavesAnErrorThatShrinksWithMorePasses) {
  for (const TieBreak& tie : kTieBreaks) {
    SCOPED_TRACE(tie.name);
    // Each compositing pass takes 2 layers; the middle rest is counted as dropped.
    test::expect_error_shrinking_with_the_pass_cap(
        "dual_depth_peeling", tie.name, [&](uint64_t cap) { return 2u * (cap - tie.passes_not_compositing); }, kSize);
    // Passes that composite nothing: nothing stored, all counted.
    const RunResult nothing = run_ok(spec_of(
        {{"tie_break", tie.name}, {"max_passes", std::to_string(tie.passes_not_compositing)}}, "quads", kQuads32, kSize));
    EXPECT_EQ(nothing.counters.fragments_stored, 0u);
    EXPECT_EQ(nothing.counters.fragments_dropped, 32u * kPixels);
  }
}

TEST(DualDepthPeeling, CoplanarStressLayersMatchTheReferenceInEverySubmissionOrder) {
  // Two of the tie per pass (from both ends), + 2.
  test::expect_coplanar_ties_like_the_reference("dual_depth_peeling", kSize, 6);
}

TEST(DualDepthPeeling, SubmissionTieBreakCompositesCoplanarLayersCompletelyInSubmissionOrder) {
  // The whole tie is at the nearest depth: all composited in one pass, + the min-max pass.
  test::expect_submission_ties_in_submission_order("dual_depth_peeling", kSize, 2);
}

TEST(DualDepthPeeling, TriangleIdTieBreakOrdersTiesAtTheFrontTheBackAndInTheMiddle) {
  constexpr int size = 16;
  constexpr uint64_t pixels = uint64_t(size) * size;
  const glm::vec4 red{0.9f, 0.1f, 0.1f, 0.5f}, green{0.1f, 0.9f, 0.1f, 0.5f}, blue{0.1f, 0.1f, 0.9f, 0.5f};
  const glm::vec4 yellow{0.9f, 0.9f, 0.1f, 0.3f}, cyan{0.1f, 0.8f, 0.8f, 0.6f}, white{0.8f, 0.8f, 0.8f, 0.4f};
  // Ties of 3 at the front and 2 at the back, one layer alone and a tie of 2
  // in the middle: selections meet inside a tie and cross tie boundaries.
  const std::string mixed = test::write_quads_gltf("dual_depth_peeling", "mixed_ties",
                                                   {{-1.0f, red}, {-1.0f, green}, {-1.0f, blue}, {-1.5f, yellow},
                                                    {-2.0f, cyan}, {-2.0f, white}, {-3.0f, green}, {-3.0f, red}});
  for (const std::string order : {"original", "reversed", "shuffled:3", "shuffled:5"}) {
    SCOPED_TRACE(order);
    const RunResult r = run_ok(spec_of({{"tie_break", "triangle_id"}}, mixed, {}, size, order));
    EXPECT_LT(r.error->max_abs, 1e-5);
    EXPECT_EQ(r.counters.fragments_stored, 8u * pixels);
    EXPECT_EQ(r.counters.fragments_dropped, 0u);
    EXPECT_EQ(r.counters.passes, 6u);
  }
}

TEST(DualDepthPeeling, DepthTiesAreAllCompositedInSubmissionOrder) {
  constexpr int size = 16;
  constexpr uint64_t pixels = uint64_t(size) * size;
  const RawParams by_submission = {{"tie_break", "submission"}};
  const glm::vec4 red{0.9f, 0.1f, 0.1f, 0.5f}, green{0.1f, 0.9f, 0.1f, 0.5f}, blue{0.1f, 0.1f, 0.9f, 0.5f};
  const glm::vec4 yellow{0.9f, 0.9f, 0.1f, 0.3f};
  // Three coplanar quads in front (their fragments tie exactly in depth), one behind.
  const std::string front_tie = test::write_quads_gltf(
      "dual_depth_peeling", "front_tie", {{-1.0f, red}, {-1.0f, green}, {-1.0f, blue}, {-2.0f, yellow}});
  // The tied fragments all sit at the nearest depth: each is blended under
  // the front in rasterisation order, which in id order is the reference's.
  const RunResult in_order = run_ok(spec_of(by_submission, front_tie, {}, size));
  EXPECT_LT(in_order.error->max_abs, 1e-5);
  EXPECT_EQ(in_order.counters.fragments_stored, 4u * pixels);
  EXPECT_EQ(in_order.counters.fragments_dropped, 0u);
  EXPECT_EQ(in_order.counters.passes, 2u);
  // Reversed submission reverses the tie: nothing is lost, the order is wrong.
  const RunResult reversed = run_ok(spec_of(by_submission, front_tie, {}, size, "reversed"));
  EXPECT_EQ(reversed.counters.fragments_stored, 4u * pixels);
  EXPECT_EQ(reversed.counters.fragments_dropped, 0u);
  EXPECT_GT(reversed.error->max_abs, 0.05);
  // A tie at the farthest depth is blended over the back in rasterisation
  // order, so there submission in id order is the reversed one: still nothing lost.
  const std::string back_tie = test::write_quads_gltf(
      "dual_depth_peeling", "back_tie", {{-1.0f, yellow}, {-2.0f, red}, {-2.0f, green}, {-2.0f, blue}});
  for (const std::string order : {"original", "reversed"}) {
    SCOPED_TRACE(order);
    const RunResult r = run_ok(spec_of(by_submission, back_tie, {}, size, order));
    EXPECT_EQ(r.counters.fragments_stored, 4u * pixels);
    EXPECT_EQ(r.counters.fragments_dropped, 0u);
    if (order == "original") {
      EXPECT_GT(r.error->max_abs, 0.05);
    } else {
      EXPECT_LT(r.error->max_abs, 1e-5);
    }
  }
  // By triangle id both ties come out as the reference's in either order,
  // one tied fragment per side and pass.
  for (const std::string& scene : {front_tie, back_tie}) {
    for (const std::string order : {"original", "reversed"}) {
      SCOPED_TRACE(scene + " " + order);
      const RunResult r = run_ok(spec_of({{"tie_break", "triangle_id"}}, scene, {}, size, order));
      EXPECT_LT(r.error->max_abs, 1e-5);
      EXPECT_EQ(r.counters.fragments_stored, 4u * pixels);
      EXPECT_EQ(r.counters.passes, 4u);
    }
  }
}

TEST(DualDepthPeeling, RejectsOutOfRangeParametersNamingThem) {
  test::expect_bad_parameters_rejected_by_name("dual_depth_peeling");
}

}  // namespace
}  // namespace oit::test
