#pragma once
// Checks both depth peelers (depth_peeling, dual_depth_peeling) must pass
// alike; each test file states only what differs: its pass counts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "tests/gl_fixture.h"

namespace oit::test {

// The frame the peelers' tests render unless they say otherwise, and the
// 32 quad layers they peel.
constexpr int kSize = 32;
constexpr uint64_t kPixels = uint64_t(kSize) * kSize;
inline const RawParams kQuads32 = {{"layers", "32"}};

// What a tie break costs a peeler: geometry passes beyond passes_for(depth),
// passes a cap spends without compositing a layer (a cap of P composites
// the layers of P minus these passes), and the bytes it allocates at kSize.
struct TieBreak {
  std::string name;
  uint64_t extra_passes;
  uint64_t passes_not_compositing;
  uint64_t bytes;
};

// The geometry passes early exit avoided (work_saved passes_avoided).
inline double passes_avoided(const RunResult& r) { return work_saved(r, "passes_avoided"); }

// Geometry passes a peeler needs for depth complexity d, before its tie
// break's extra passes: d for depth peeling, ceil(d / 2) for dual.
using PassesForDepth = uint64_t (*)(uint64_t depth);

// 8 quad layers: early exit stops right after the last layer (passes_for(8)
// + extra); without it exactly `no_exit_cap` passes run, the extra ones
// composite nothing and the image is the same; passes_avoided counts what
// early exit saved of the default 64, and nothing without it or under a
// cap (`small_cap`) that early exit never reaches.
inline void expect_early_exit_and_caps(const std::string& technique, const std::string& tie_break, uint64_t extra,
                                       PassesForDepth passes_for, int no_exit_cap, int small_cap, int size) {
  const RawParams layers8 = {{"layers", "8"}};
  const RunResult early = run_ok(one_frame(technique, {{"tie_break", tie_break}}, "quads", layers8, size));
  EXPECT_EQ(early.max_depth_complexity, 8u);
  EXPECT_EQ(early.counters.passes, passes_for(8) + extra);
  EXPECT_LT(early.error->max_abs, 1e-5);
  const RunResult all = run_ok(one_frame(
      technique, {{"tie_break", tie_break}, {"early_exit", "false"}, {"max_passes", std::to_string(no_exit_cap)}},
      "quads", layers8, size));
  EXPECT_EQ(all.counters.passes, uint64_t(no_exit_cap));
  EXPECT_LT(all.error->max_abs, 1e-5);
  EXPECT_EQ(all.counters.fragments_stored, 8u * uint64_t(size) * uint64_t(size));
  EXPECT_EQ(all.counters.fragments_dropped, 0u);
  EXPECT_EQ(all.image.rgba, early.image.rgba);
  EXPECT_EQ(passes_avoided(early), double(64 - passes_for(8) - extra));
  EXPECT_EQ(passes_avoided(all), 0.0);
  const RunResult capped = run_ok(one_frame(
      technique, {{"tie_break", tie_break}, {"max_passes", std::to_string(small_cap)}}, "quads", layers8, size));
  EXPECT_EQ(capped.counters.passes, uint64_t(small_cap));
  EXPECT_EQ(passes_avoided(capped), 0.0);
}

// passes_avoided of the default 64 passes on 32 quad layers and on the
// spheres, whose uneven depth lets the deepest pixel decide the passes.
inline void expect_passes_avoided_on_quads_and_spheres(const std::string& technique, const std::string& tie_break,
                                                       uint64_t extra, PassesForDepth passes_for) {
  const RunResult quads = run_ok(one_frame(technique, {{"tie_break", tie_break}}, "quads", {{"layers", "32"}}, 64));
  EXPECT_LT(quads.error->max_abs, 1e-5);
  EXPECT_EQ(passes_avoided(quads), double(64 - passes_for(32) - extra));
  const RunResult spheres = run_ok(one_frame(technique, {{"tie_break", tie_break}}, "spheres", {}, 64));
  EXPECT_LT(spheres.error->max_abs, 1e-5);
  EXPECT_EQ(passes_avoided(spheres), double(64 - passes_for(spheres.max_depth_complexity) - extra));
}

// stress_layers with gap 0: 8 full-screen layers at one depth, so every
// pixel holds an 8-way tie that only the stable triangle id orders.
// tie_break=triangle_id matches the reference in every submission order
// and seed, every fragment composited, in `passes` passes.
inline void expect_coplanar_ties_like_the_reference(const std::string& technique, int size, uint64_t passes) {
  const uint64_t pixels = uint64_t(size) * uint64_t(size);
  for (const std::string seed : {"1", "2"}) {
    for (const std::string order : {"original", "reversed", "shuffled:3"}) {
      SCOPED_TRACE("seed " + seed + " " + order);
      const RunResult r = run_ok(one_frame(technique, {{"tie_break", "triangle_id"}}, "stress_layers",
                                           {{"gap", "0"}, {"seed", seed}}, size, order));
      EXPECT_EQ(r.max_depth_complexity, 8u);
      EXPECT_LT(r.error->max_abs, 1e-5);
      EXPECT_EQ(r.counters.fragments_stored, 8u * pixels);
      EXPECT_EQ(r.counters.fragments_dropped, 0u);
      EXPECT_EQ(r.counters.passes, passes);
    }
  }
}

// The same tie with tie_break=submission: every tied fragment composited in
// `passes` passes, none lost, but in submission order, so the image moves
// with the order.
inline void expect_submission_ties_in_submission_order(const std::string& technique, int size, uint64_t passes) {
  const uint64_t pixels = uint64_t(size) * uint64_t(size);
  Image original;
  for (const std::string order : {"original", "reversed", "shuffled:3"}) {
    SCOPED_TRACE(order);
    const RunResult r =
        run_ok(one_frame(technique, {{"tie_break", "submission"}}, "stress_layers", {{"gap", "0"}}, size, order));
    for (float v : r.image.rgba) ASSERT_TRUE(std::isfinite(v));
    EXPECT_EQ(r.counters.fragments_stored, 8u * pixels);
    EXPECT_EQ(r.counters.fragments_dropped, 0u);
    EXPECT_EQ(r.counters.passes, passes);
    if (order == "original") original = r.image;
    else EXPECT_GT(max_abs_difference(r.image, original), 0.05);
  }
}

// 32 quad layers, in the original and a shuffled order: exact against the
// reference, every fragment peeled and counted, in `passes` passes with
// `bytes` allocated.
inline void expect_exact_on_thirty_two_quads(const std::string& technique, const std::string& tie_break,
                                             uint64_t passes, uint64_t bytes, int size) {
  const uint64_t pixels = uint64_t(size) * uint64_t(size);
  for (const std::string order : {"original", "shuffled:7"}) {
    SCOPED_TRACE(tie_break + " " + order);
    const RunResult r =
        run_ok(one_frame(technique, {{"tie_break", tie_break}}, "quads", {{"layers", "32"}}, size, order));
    ASSERT_TRUE(r.error.has_value());
    // Layers are blended in float, the reference in double: only rounding separates them.
    EXPECT_LT(r.error->max_abs, 1e-5);
    EXPECT_EQ(r.counters.fragments_stored, 32u * pixels);
    EXPECT_EQ(r.counters.fragments_dropped, 0u);
    EXPECT_EQ(r.counters.passes, passes);
    EXPECT_EQ(r.counters.bytes_allocated, bytes);
  }
}

// The lit spheres (48 x 48), in the original and a shuffled order: exact,
// every fragment counted, passes_for(depth complexity) + extra passes.
inline void expect_exact_on_lit_spheres(const std::string& technique, const std::string& tie_break, uint64_t extra,
                                        PassesForDepth passes_for) {
  for (const std::string order : {"original", "shuffled:7"}) {
    SCOPED_TRACE(tie_break + " " + order);
    const RunResult r = run_ok(one_frame(technique, {{"tie_break", tie_break}}, "spheres", {}, 48, order));
    ASSERT_TRUE(r.error.has_value());
    ASSERT_GE(r.max_depth_complexity, 4u) << "the spheres must overlap for this test to mean anything";
    EXPECT_LT(r.error->max_abs, 1e-5);
    EXPECT_EQ(r.counters.fragments_stored, r.scene_fragments);
    EXPECT_EQ(r.counters.fragments_dropped, 0u);
    EXPECT_EQ(r.counters.passes, passes_for(r.max_depth_complexity) + extra);
  }
}

// What every tie break of a peeler (`ties`: each with a name and the
// extra_passes it adds) must do alike: expect_exact_on_lit_spheres,
// expect_early_exit_and_caps (`no_exit_cap`, `small_cap`) and
// expect_passes_avoided_on_quads_and_spheres.
template <class TieBreaks>
void expect_every_tie_break_exact_and_stopping_early(const std::string& technique, const TieBreaks& ties,
                                                     PassesForDepth passes_for, int no_exit_cap, int small_cap,
                                                     int size) {
  for (const auto& tie : ties) {
    SCOPED_TRACE(tie.name);
    expect_exact_on_lit_spheres(technique, tie.name, tie.extra_passes, passes_for);
    expect_early_exit_and_caps(technique, tie.name, tie.extra_passes, passes_for, no_exit_cap, small_cap, size);
    expect_passes_avoided_on_quads_and_spheres(technique, tie.name, tie.extra_passes, passes_for);
  }
}

// Layers of 32 quads a pass cap of `cap` passes composites.
using LayersUnderCap = std::function<uint64_t(uint64_t cap)>;

// 32 quad layers under caps of 4, 8 and 16 passes: exactly `cap` passes, an
// error that shrinks strictly as the cap grows, and the layers the cap
// leaves out counted as dropped.
inline void expect_error_shrinking_with_the_pass_cap(const std::string& technique, const std::string& tie_break,
                                                     const LayersUnderCap& layers_under, int size) {
  const uint64_t pixels = uint64_t(size) * uint64_t(size);
  double previous_error = 2.0;
  for (int cap : {4, 8, 16}) {
    SCOPED_TRACE(tie_break + " max_passes=" + std::to_string(cap));
    const RunResult r = run_ok(one_frame(technique, {{"tie_break", tie_break}, {"max_passes", std::to_string(cap)}},
                                         "quads", {{"layers", "32"}}, size));
    ASSERT_TRUE(r.error.has_value());
    EXPECT_GT(r.error->max_abs, 1e-4);
    EXPECT_LT(r.error->max_abs, previous_error);
    previous_error = r.error->max_abs;
    EXPECT_EQ(r.counters.passes, uint64_t(cap));
    const uint64_t layers = layers_under(uint64_t(cap));
    EXPECT_EQ(r.counters.fragments_stored, layers * pixels);
    EXPECT_EQ(r.counters.fragments_dropped, (32u - layers) * pixels);
  }
}

// max_passes, early_exit and tie_break out of range: an error row naming
// the parameter (and, for max_passes, the technique).
inline void expect_bad_parameters_rejected_by_name(const std::string& technique) {
  for (const std::string bad : {"0", "4097", "many"}) {
    const RunResult r = harness().run(one_frame(technique, {{"max_passes", bad}}, "quads", {{"layers", "2"}}, 8));
    EXPECT_EQ(r.status, RunStatus::error);
    EXPECT_NE(r.message.find("max_passes"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find(technique), std::string::npos) << r.message;
  }
  for (const auto& [name, bad] : {std::pair{"early_exit", "maybe"}, std::pair{"tie_break", "depth"}}) {
    const RunResult r = harness().run(one_frame(technique, {{name, bad}}, "quads", {{"layers", "2"}}, 8));
    EXPECT_EQ(r.status, RunStatus::error);
    EXPECT_NE(r.message.find(name), std::string::npos) << r.message;
  }
}

}  // namespace oit::test
