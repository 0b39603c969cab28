// linked_list: the generated sorting networks on the CPU, then every sort
// variant against the exact reference (quads, spheres, shuffled submission),
// pool overflow and regrowth, counted truncation, and parameter errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "../algorithms/linked_list/sorting_network.h"
#include "gl_fixture.h"
#include "stacked_quads.h"

namespace oit {
namespace {

using linked_list::apply_network;
using linked_list::odd_even_merge_sort;

const std::vector<std::string> kSorts = {"insertion", "selection", "network"};
// Float blending of up to 32 layers against the reference's double blend.
constexpr double kFloatTolerance = 1e-5;

TEST(LinkedListNetwork, SortsEveryZeroOneInputUpToSixteen) {
  // 0-1 principle: a comparator network sorts everything iff it sorts all 0-1 inputs.
  for (uint32_t n = 1; n <= 16; ++n) {
    const auto network = odd_even_merge_sort(n);
    for (uint32_t bits = 0; bits < (1u << n); ++bits) {
      std::vector<uint32_t> values(n);
      for (uint32_t i = 0; i < n; ++i) values[i] = (bits >> i) & 1u;
      apply_network(network, values);
      ASSERT_TRUE(std::is_sorted(values.begin(), values.end())) << "n=" << n << " input " << bits;
    }
  }
}

TEST(LinkedListNetwork, SortsRandomPermutationsOfLargeAndOddSizes) {
  std::mt19937 rng(11);
  for (uint32_t n : {12u, 24u, 32u, 33u, 64u, 100u, 128u}) {
    const auto network = odd_even_merge_sort(n);
    for (int trial = 0; trial < 200; ++trial) {
      std::vector<uint32_t> values(n);
      std::iota(values.begin(), values.end(), 0u);
      std::shuffle(values.begin(), values.end(), rng);
      apply_network(network, values);
      ASSERT_TRUE(std::is_sorted(values.begin(), values.end())) << "n=" << n;
    }
  }
  // Batcher's comparator counts for powers of two: (p^2 - p + 4) 2^(p-2) - 1.
  EXPECT_EQ(odd_even_merge_sort(32).size(), 191u);
  EXPECT_EQ(odd_even_merge_sort(64).size(), 543u);
}

TEST(LinkedList, EverySortMatchesTheReferenceOnThirtyTwoQuads) {
  for (const std::string& sort : kSorts) {
    const RunResult r = test::render_once("linked_list", {{"sort", sort}}, "quads", {{"layers", "32"}}, 48, 48);
    ASSERT_TRUE(r.error.has_value()) << sort;
    EXPECT_LT(r.error->max_abs, kFloatTolerance) << sort;
    EXPECT_EQ(r.counters.fragments_stored, 32u * 48u * 48u) << sort;
    EXPECT_EQ(r.counters.fragments_dropped, 0u) << sort;
    EXPECT_EQ(r.counters.passes, 2u) << sort << ": the default pool (8 per pixel) overflows once";
  }
}

TEST(LinkedList, EverySortMatchesTheReferenceOnSpheres) {
  for (const std::string& sort : kSorts) {
    const RunResult r = test::render_once("linked_list", {{"sort", sort}}, "spheres", {}, 48, 48);
    ASSERT_TRUE(r.error.has_value()) << sort;
    EXPECT_LT(r.error->max_abs, kFloatTolerance) << sort;
    EXPECT_EQ(r.counters.fragments_stored, r.scene_fragments) << sort;
    EXPECT_EQ(r.counters.fragments_dropped, 0u) << sort;
  }
}

TEST(LinkedList, EverySortIsOrderIndependent) {
  for (const std::string& sort : kSorts) {
    RunSpec spec;
    spec.technique = "linked_list";
    spec.params = {{"sort", sort}};
    spec.scene = "quads";
    spec.scene_params = {{"layers", "32"}};
    spec.submission_order = "shuffled:7";
    spec.width = 48;
    spec.height = 48;
    spec.warmup = 0;
    spec.frames = 1;
    const RunResult r = test::harness().run(spec);
    ASSERT_EQ(r.status, RunStatus::ok) << r.message;
    EXPECT_LT(r.error->max_abs, kFloatTolerance) << sort;
  }
}

TEST(LinkedList, PoolOverflowGrowsAndReRendersWithoutLoss) {
  const int w = 32, h = 32;
  const RunResult r = test::render_once("linked_list", {{"initial_nodes_per_pixel", "1"}}, "quads",
                                        {{"layers", "16"}}, w, h);
  EXPECT_GE(r.counters.overflow_retries, 1u);
  EXPECT_EQ(r.counters.fragments_stored, 16u * w * h);
  EXPECT_EQ(r.counters.fragments_dropped, 0u);
  EXPECT_LT(r.error->max_abs, kFloatTolerance);
  // The grown pool holds the 1.25x slack: heads + lengths (8 B/pixel) + 32 B/node + counters.
  const uint64_t nodes = uint64_t(16.0 * w * h * 1.25) + 1;
  EXPECT_EQ(r.counters.bytes_allocated, 8u * w * h + 32u * nodes + 12u);
  const RunResult roomy = test::render_once("linked_list", {{"initial_nodes_per_pixel", "16"}}, "quads",
                                            {{"layers", "16"}}, w, h);
  EXPECT_EQ(roomy.counters.overflow_retries, 0u);
  EXPECT_EQ(roomy.counters.passes, 1u);
}

// Front-to-back composite (double) of the `kept` nearest layers of the quad stack over black.
glm::dvec4 nearest_layers_composite(int layers, int kept) {
  StackedQuadsParams p;
  p.layers = layers;
  auto stack = stacked_quad_layers(p);
  std::sort(stack.begin(), stack.end(), [](const QuadLayer& a, const QuadLayer& b) { return a.eye_distance < b.eye_distance; });
  glm::dvec3 accumulated(0.0);
  double transmittance = 1.0;
  for (int i = 0; i < kept; ++i) {
    const glm::dvec4 c(stack[size_t(i)].color);
    accumulated += transmittance * c.a * glm::dvec3(c);
    transmittance *= 1.0 - c.a;
  }
  return glm::dvec4(accumulated, 1.0 - transmittance);
}

TEST(LinkedList, TruncationKeepsTheNearestFragmentsAndCountsTheRest) {
  const int w = 24, h = 24, layers = 32;
  const RunResult unsorted = test::render_once("unsorted", {}, "quads", {{"layers", "32"}}, w, h);
  // 12 is below the list length and not a power of two (pruned network); 1 is the extreme.
  for (int kept : {12, 1}) {
    const glm::dvec4 expected = nearest_layers_composite(layers, kept);
    // Everything behind the kept layers is missing: transmittance 0.7^kept bounds the error.
    const double bound = std::pow(0.7, kept) + kFloatTolerance;
    for (const std::string& sort : kSorts) {
      const RunResult r = test::render_once("linked_list", {{"sort", sort}, {"max_per_pixel", std::to_string(kept)}},
                                            "quads", {{"layers", "32"}}, w, h);
      EXPECT_EQ(r.counters.fragments_dropped, uint64_t(layers - kept) * w * h) << sort;
      EXPECT_EQ(r.counters.fragments_stored, uint64_t(kept) * w * h) << sort;
      double worst = 0.0;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < 4; ++c) {
            ASSERT_TRUE(std::isfinite(r.image.at(x, y, c)));
            worst = std::max(worst, std::abs(double(r.image.at(x, y, c)) - expected[c]));
          }
      EXPECT_LT(worst, kFloatTolerance) << sort << " kept " << kept << ": not the nearest layers";
      EXPECT_GT(r.error->max_abs, 0.0) << sort;
      EXPECT_LT(r.error->max_abs, bound) << sort;
      // Keeping a single layer loses more than unsorted blending does; twelve lose less.
      if (kept == 12) {
        EXPECT_LT(r.error->max_abs, unsorted.error->max_abs) << sort;
      }
    }
  }
}

TEST(LinkedList, EverySortKeepsTheSameNearestFragmentsOnSpheres) {
  // Lists of varying length, most longer than 2: all sorts must keep the same two nearest.
  std::vector<RunResult> runs;
  for (const std::string& sort : kSorts)
    runs.push_back(test::render_once("linked_list", {{"sort", sort}, {"max_per_pixel", "2"}}, "spheres", {}, 32, 32));
  const RunResult& first = runs.front();
  EXPECT_GT(first.counters.fragments_dropped, 0u);
  EXPECT_EQ(first.counters.fragments_stored + first.counters.fragments_dropped, first.scene_fragments);
  for (const RunResult& r : runs) {
    EXPECT_EQ(r.counters.fragments_dropped, first.counters.fragments_dropped);
    EXPECT_GT(r.error->max_abs, 0.0);
    double worst = 0.0;
    for (size_t i = 0; i < r.image.rgba.size(); ++i)
      worst = std::max(worst, std::abs(double(r.image.rgba[i]) - double(first.image.rgba[i])));
    EXPECT_LT(worst, 1e-6);
  }
}

TEST(LinkedList, NetworkFallsBackForListsLongerThanItsLargestNetwork) {
  // 136 layers need a 256-element array: beyond the unrolled networks, resolved by insertion sort.
  const RunResult r = test::render_once("linked_list", {{"sort", "network"}, {"max_per_pixel", "1024"}}, "quads",
                                        {{"layers", "136"}, {"alpha", "0.05"}}, 8, 8);
  EXPECT_EQ(r.counters.fragments_dropped, 0u);
  EXPECT_LT(r.error->max_abs, kFloatTolerance);
}

TEST(LinkedList, UnknownSortIsAnErrorNamingTheParameter) {
  RunSpec spec;
  spec.technique = "linked_list";
  spec.params = {{"sort", "bubble"}};
  spec.width = 8;
  spec.height = 8;
  spec.warmup = 0;
  spec.frames = 1;
  const RunResult r = test::harness().run(spec);
  EXPECT_EQ(r.status, RunStatus::error);
  EXPECT_NE(r.message.find("sort"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("bubble"), std::string::npos) << r.message;
}

TEST(LinkedList, OutOfRangeArraySizeIsAnError) {
  RunSpec spec;
  spec.technique = "linked_list";
  spec.params = {{"max_per_pixel", "0"}};
  spec.width = 8;
  spec.height = 8;
  const RunResult r = test::harness().run(spec);
  EXPECT_EQ(r.status, RunStatus::error);
  EXPECT_NE(r.message.find("max_per_pixel"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace oit
