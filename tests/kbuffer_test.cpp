// The dual-pass k-buffer: exact when k covers the depth complexity (in any
// submission order, and with tied depths), truncation error that shrinks as
// k grows with every dropped fragment counted, the unsorted tail blend, and
// parameter checks.
#include <gtest/gtest.h>

#include <cmath>

#include "harness/output/error_metrics.h"
#include "tests/gl_fixture.h"
#include "tests/kbuffer_checks.h"

namespace oit {
namespace {

constexpr int kSize = 32;
const RawParams kQuads32 = {{"layers", "32"}};

const test::OneFrameOf spec_of{"kbuffer"};
using test::run_ok;

bool identical(const Image& a, const Image& b) { return a.width == b.width && a.height == b.height && a.rgba == b.rgba; }

TEST(KBuffer, ExactOnQuadsWhenKCoversEveryLayer) {
  const RunResult r = run_ok(spec_of({{"k", "32"}}, "quads", kQuads32, kSize));
  ASSERT_TRUE(r.error.has_value());
  EXPECT_EQ(r.max_depth_complexity, 32u);
  // Slots hold float colours and are blended front to back in float; the
  // reference blends in double: only float rounding separates them.
  EXPECT_LT(r.error->max_abs, 1e-5);
  const uint64_t pixels = kSize * kSize;
  EXPECT_EQ(r.counters.fragments_stored, 32u * pixels);
  EXPECT_EQ(r.counters.fragments_dropped, 0u);
  EXPECT_EQ(r.counters.passes, 2u);
  EXPECT_EQ(r.counters.bytes_allocated, pixels * 32u * (4u + 4u + 16u) + 8u);
}

TEST(KBuffer, ExactOnSpheresInAnySubmissionOrder) {
  const RunResult original = run_ok(spec_of({{"k", "32"}}, "spheres", {}, 48));
  ASSERT_TRUE(original.error.has_value());
  ASSERT_LE(original.max_depth_complexity, 32u) << "k=32 must cover the scene for this test to mean anything";
  ASSERT_GE(original.max_depth_complexity, 2u);
  EXPECT_LT(original.error->max_abs, 1e-5);
  EXPECT_EQ(original.counters.fragments_stored, original.scene_fragments);
  EXPECT_EQ(original.counters.fragments_dropped, 0u);
  for (const char* order : {"shuffled:7", "reversed"}) {
    const RunResult reordered = run_ok(spec_of({{"k", "32"}}, "spheres", {}, 48, order));
    ASSERT_TRUE(reordered.error.has_value());
    EXPECT_LT(reordered.error->max_abs, 1e-5) << order;
    // The same fragments in the same sorted order: the very same image.
    EXPECT_TRUE(identical(reordered.image, original.image)) << order;
  }
}

TEST(KBuffer, ExactOnShuffledQuads) {
  const RunResult original = run_ok(spec_of({{"k", "32"}}, "quads", kQuads32, kSize));
  const RunResult shuffled = run_ok(spec_of({{"k", "32"}}, "quads", kQuads32, kSize, "shuffled:7"));
  ASSERT_TRUE(shuffled.error.has_value());
  EXPECT_LT(shuffled.error->max_abs, 1e-5);
  EXPECT_TRUE(identical(shuffled.image, original.image));
}

// A glTF scene of three full-screen unlit quads at the SAME depth (identical
// vertices, different colours) in front of a fourth quad: every pixel has a
// run of three tied depth keys. Triangle ids follow the file order, so the
// exact order of the tie is red, green, blue.
std::string write_tied_quads_gltf() {
  return test::write_quads_gltf("kbuffer", "tied",
                                {{-2.0f, {0.9f, 0.1f, 0.1f, 0.5f}},
                                 {-2.0f, {0.1f, 0.9f, 0.1f, 0.6f}},
                                 {-2.0f, {0.1f, 0.1f, 0.9f, 0.7f}},
                                 {-3.0f, {0.8f, 0.8f, 0.2f, 0.4f}}});
}

TEST(KBuffer, TiedDepthsAreOrderedByTriangleIdInAnySubmissionOrder) {
  const std::string path = write_tied_quads_gltf();
  const uint64_t pixels = 16 * 16;
  const RunResult original = run_ok(spec_of({{"k", "4"}}, path, {}, 16));
  ASSERT_TRUE(original.error.has_value());
  ASSERT_EQ(original.max_depth_complexity, 4u);
  EXPECT_LT(original.error->max_abs, 1e-6);
  EXPECT_EQ(original.counters.fragments_stored, 4u * pixels);
  for (const char* order : {"reversed", "shuffled:7"}) {
    const RunResult reordered = run_ok(spec_of({{"k", "4"}}, path, {}, 16, order));
    ASSERT_TRUE(reordered.error.has_value());
    EXPECT_LT(reordered.error->max_abs, 1e-6) << order;
  }
  // The tie matters: unsorted blending of the original submission (nearest
  // first, so blended as if it were farthest) is clearly wrong.
  RunSpec unsorted = spec_of({}, path, {}, 16);
  unsorted.technique = "unsorted";
  EXPECT_GT(run_ok(unsorted).error->max_abs, 0.05);
  // k = 2 cuts through the tied run: two of the three tied fragments and the
  // far quad cannot stay, and each one lost is counted.
  const RunResult cut = run_ok(spec_of({{"k", "2"}}, path, {}, 16));
  EXPECT_EQ(cut.counters.fragments_stored, 2u * pixels);
  EXPECT_EQ(cut.counters.fragments_dropped, 2u * pixels);
}

TEST(KBuffer, TruncationErrorShrinksAsKGrowsAndEveryDropIsCounted) {
  const uint64_t pixels = kSize * kSize;
  double previous_error = INFINITY;
  for (int k : {4, 8, 16}) {
    const RunResult r = run_ok(spec_of({{"k", std::to_string(k)}}, "quads", kQuads32, kSize));
    ASSERT_TRUE(r.error.has_value());
    // Dropping the far layers loses their colour: visibly wrong, but less so with more slots.
    EXPECT_GT(r.error->max_abs, 1e-4) << "k=" << k;
    EXPECT_LT(r.error->max_abs, previous_error) << "k=" << k;
    previous_error = r.error->max_abs;
    EXPECT_EQ(r.counters.fragments_stored, uint64_t(k) * pixels) << "k=" << k;
    EXPECT_EQ(r.counters.fragments_dropped, uint64_t(32 - k) * pixels) << "k=" << k;
  }
}

TEST(KBuffer, TailBlendBeatsDroppingTheTail) {
  const uint64_t pixels = kSize * kSize;
  const RunResult dropped = run_ok(spec_of({{"k", "8"}, {"tail", "drop"}}, "quads", kQuads32, kSize));
  const RunResult blended = run_ok(spec_of({{"k", "8"}, {"tail", "blend"}}, "quads", kQuads32, kSize));
  ASSERT_TRUE(dropped.error.has_value() && blended.error.has_value());
  EXPECT_GT(blended.error->max_abs, 0.0);
  EXPECT_LT(blended.error->max_abs, dropped.error->max_abs);
  EXPECT_LT(blended.error->rmse, dropped.error->rmse);
  // The tail is approximated, not lost: nothing is dropped.
  EXPECT_EQ(blended.counters.fragments_stored, 8u * pixels);
  EXPECT_EQ(blended.counters.fragments_dropped, 0u);
  // The tail targets (RGBA16F + R16F) are counted.
  EXPECT_EQ(blended.counters.bytes_allocated, dropped.counters.bytes_allocated + pixels * 10u);
}

TEST(KBuffer, TailBlendIsExactWhenThereIsNoTail) {
  // With k >= layers the tail targets stay empty and must not disturb the image.
  const RunResult r = run_ok(spec_of({{"k", "8"}, {"tail", "blend"}}, "quads", {{"layers", "8"}}, kSize));
  ASSERT_TRUE(r.error.has_value());
  EXPECT_LT(r.error->max_abs, 1e-5);
}

TEST(KBuffer, RejectsKOutsideOneToSixtyFour) {
  for (const char* k : {"0", "65", "automatic"}) {
    const RunResult r = test::harness().run(spec_of({{"k", k}}, "quads", {{"layers", "2"}}, 8));
    EXPECT_EQ(r.status, RunStatus::error) << "k=" << k;
    EXPECT_NE(r.message.find("'k'"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("[1, 64]"), std::string::npos) << r.message;
  }
  const RunResult r = test::harness().run(spec_of({{"tail", "keep"}}, "quads", {{"layers", "2"}}, 8));
  EXPECT_EQ(r.status, RunStatus::error);
  EXPECT_NE(r.message.find("'tail'"), std::string::npos) << r.message;
}

// k=auto: a counting pass sizes k from the view's longest list, so on the
// 32-layer quads it is exact, equals the worst-case k=64 image and allocates
// a third of its memory (plus 4 bytes per pixel of counters).
TEST(KBuffer, AutoKIsTheViewsDepthComplexityAndMatchesTheWorstCaseK) {
  constexpr int size = 64;
  const uint64_t pixels = size * size;
  RunSpec spec = spec_of({{"k", "auto"}}, "quads", kQuads32, size);
  spec.frames = 2;  // the second frame reuses the storage of the first
  const RunResult automatic = run_ok(spec);
  const RunResult worst_case = run_ok(spec_of({{"k", "64"}}, "quads", kQuads32, size));
  ASSERT_TRUE(automatic.error.has_value());
  EXPECT_LT(automatic.error->max_abs, 1e-5);
  EXPECT_LE(compare_images(automatic.image, worst_case.image).max_abs, 1e-5);
  // 24-byte nodes and an 8-byte counter block.
  test::expect_auto_k_on_thirty_two_layers(automatic, worst_case, pixels, 24u, 8u);

  const RunResult four = run_ok(spec_of({{"k", "auto"}}, "quads", {{"layers", "4"}}, size));
  ASSERT_TRUE(four.error.has_value());
  EXPECT_EQ(test::extra_counter(four, "k_used"), 4.0);
  EXPECT_LT(four.error->max_abs, 1e-5);
  EXPECT_EQ(four.counters.bytes_allocated, pixels * 4u * 24u + 8u + pixels * 4u);
}

TEST(KBuffer, AutoKIsCappedByItsMemoryBudgetAndCountsWhatItDrops) {
  // 1 MiB of slots at 64x64 (24 bytes each) holds 10 per pixel, fewer than
  // the 32 layers: k=auto then behaves exactly like k=10.
  constexpr int size = 64;
  const uint64_t pixels = size * size;
  const RunResult capped = run_ok(spec_of({{"k", "auto"}, {"auto_k_memory_mb", "1"}}, "quads", kQuads32, size));
  const RunResult fixed = run_ok(spec_of({{"k", "10"}}, "quads", kQuads32, size));
  EXPECT_EQ(test::extra_counter(capped, "k_used"), 10.0);
  EXPECT_EQ(test::extra_counter(capped, "k_cap"), 10.0);
  EXPECT_EQ(test::extra_counter(capped, "longest_list"), 32.0);
  EXPECT_EQ(test::extra_counter(capped, "k_capped"), 1.0);
  EXPECT_EQ(capped.counters.fragments_stored, 10u * pixels);
  EXPECT_EQ(capped.counters.fragments_dropped, 22u * pixels);
  EXPECT_TRUE(identical(capped.image, fixed.image));
  EXPECT_LE(capped.counters.bytes_allocated - pixels * 4u, uint64_t(1) << 20);
}

// slot_layout=paper: murray2016's 8-byte slot (key + RGBA8 colour). The
// image is the reference within the RGBA8 packing bound (full: float
// rounding), exactly 8 bytes a slot, the same counts.
TEST(KBuffer, PaperSlotsTakeEightBytesAndStayWithinTheRgba8PackingBound) {
  const uint64_t pixels = kSize * kSize;
  const RunResult paper = run_ok(spec_of({{"k", "32"}, {"slot_layout", "paper"}}, "quads", kQuads32, kSize));
  const RunResult full = run_ok(spec_of({{"k", "32"}}, "quads", kQuads32, kSize));
  ASSERT_TRUE(paper.error.has_value());
  EXPECT_LE(paper.error->max_abs, test::packing_bound(0.3, 32));
  EXPECT_LE(test::max_abs_difference(paper.image, full.image), test::packing_bound(0.3, 32));
  EXPECT_GT(paper.error->max_abs, full.error->max_abs) << "the colours were quantised";
  EXPECT_EQ(paper.counters.bytes_allocated, pixels * 32u * 8u + 8u);
  EXPECT_EQ(paper.counters.fragments_stored, 32u * pixels);
  EXPECT_EQ(paper.counters.fragments_dropped, 0u);
  const RunResult cut = run_ok(spec_of({{"k", "8"}, {"slot_layout", "paper"}}, "quads", kQuads32, kSize));
  EXPECT_EQ(cut.counters.fragments_stored, 8u * pixels);
  EXPECT_EQ(cut.counters.fragments_dropped, 24u * pixels);
}

// Without the owner word, ties are ordered by packed colour: the image does
// not depend on the submission order (though it is not the reference's
// triangle-id order), and every tied fragment keeps a slot of its own.
TEST(KBuffer, PaperSlotsOrderTiesByColourInAnySubmissionOrder) {
  const std::string path = write_tied_quads_gltf();
  const RawParams paper = {{"k", "4"}, {"slot_layout", "paper"}};
  const RunResult original = run_ok(spec_of(paper, path, {}, 16));
  EXPECT_EQ(original.counters.fragments_stored, 4u * 16u * 16u);
  for (const char* order : {"reversed", "shuffled:7"})
    EXPECT_TRUE(identical(run_ok(spec_of(paper, path, {}, 16, order)).image, original.image)) << order;
  const RawParams deep = {{"k", "32"}, {"slot_layout", "paper"}};
  const RunResult spheres = run_ok(spec_of(deep, "spheres", {}, 48));
  EXPECT_EQ(spheres.counters.fragments_dropped, 0u);
  EXPECT_TRUE(identical(run_ok(spec_of(deep, "spheres", {}, 48, "shuffled:3")).image, spheres.image));
  EXPECT_LE(spheres.error->max_abs, test::packing_bound(0.4, 6));
}

TEST(KBuffer, DeclaresTheAutoKSwitch) {
  const auto& switches = builtin_techniques().get("kbuffer").adaptive_switches;
  ASSERT_EQ(switches.size(), 1u);
  EXPECT_EQ(switches[0].feature, "k_auto");
  EXPECT_EQ(switches[0].on, (RawParams{{"k", "auto"}}));
  EXPECT_EQ(switches[0].off, (RawParams{{"k", "64"}}));
}

}  // namespace
}  // namespace oit
