#pragma once
// Checks both depth peelers (depth_peeling, dual_depth_peeling) must pass
// alike; each test file states only what differs: its pass counts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "tests/gl_fixture.h"

namespace oit::test {

// The geometry passes early exit avoided (work_saved passes_avoided).
inline double passes_avoided(const RunResult& r) {
  if (auto value = find_figure(r.counters.work_saved, "passes_avoided")) return *value;
  ADD_FAILURE() << "no passes_avoided in work_saved";
  return -1.0;
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

}  // namespace oit::test
