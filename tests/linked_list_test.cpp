// linked_list: the generated sorting networks on the CPU, then every sort
// variant against the exact reference (quads, spheres, shuffled submission),
// pool overflow and regrowth, counted truncation, parameter errors, and the
// adaptive paths: pool_sizing (previous_frame, count, worst_case) and
// length_classes, with their exact work_saved figures.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>
#include <random>

#include "algorithms/linked_list/length_classes.h"
#include "algorithms/linked_list/sorting_network.h"
#include "harness/run/complexity.h"
#include "tests/gl_fixture.h"
#include "scenes/scene_library.h"
#include "scenes/stacked_quads.h"

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

TEST(LinkedListNetwork, LengthClassesArePowersOfTwoUpToTheArraySize) {
  using linked_list::class_sizes;
  EXPECT_EQ(class_sizes(8, 64), (std::vector<uint32_t>{8, 16, 32, 64}));
  EXPECT_EQ(class_sizes(8, 100), (std::vector<uint32_t>{8, 16, 32, 64, 100}));
  EXPECT_EQ(class_sizes(8, 128).size(), 5u);
  EXPECT_EQ(class_sizes(8, 12), (std::vector<uint32_t>{8, 12}));
  EXPECT_EQ(class_sizes(8, 8), (std::vector<uint32_t>{8}));
  EXPECT_EQ(class_sizes(1, 1), (std::vector<uint32_t>{1}));
  using linked_list::class_index;
  const std::vector<uint32_t> sizes = {1, 8, 16, 32};
  EXPECT_EQ(class_index(sizes, 0), 0u);
  EXPECT_EQ(class_index(sizes, 1), 0u);
  EXPECT_EQ(class_index(sizes, 2), 1u);
  EXPECT_EQ(class_index(sizes, 16), 2u);
  EXPECT_EQ(class_index(sizes, 17), 3u);
  EXPECT_EQ(class_index(sizes, 40), 3u) << "truncated lists: the last class";
  // A 5x5 image: tiles 2x2, the edge tiles partial.
  std::vector<uint32_t> lengths(25, 0u);
  lengths[0] = 3;           // tile 0
  lengths[4] = 7;           // (4,0): tile 1
  lengths[4 * 5 + 0] = 2;   // (0,4): tile 2
  lengths[4 * 5 + 4] = 9;   // (4,4): tile 3
  lengths[3 * 5 + 3] = 5;   // (3,3): tile 0
  EXPECT_EQ(linked_list::tile_longest(lengths, 5, 5), (std::vector<uint32_t>{5, 7, 2, 9}));
}

TEST(LinkedList, NetworkByLengthClassMatchesTheReferenceOnUnevenLists) {
  // Lists of 2..23 fragments: tiles of the 8-, 16- and 32-element networks.
  // 37x29 is no multiple of the 4x4 tiles: the edge tiles are partial.
  const RunResult r = test::render_once("linked_list", {{"sort", "network"}}, "random_quads", {}, 37, 29);
  ASSERT_GT(r.max_depth_complexity, 16u);
  ASSERT_LT(r.mean_depth_complexity, 12.5);
  EXPECT_LT(r.error->max_abs, kFloatTolerance);
  EXPECT_EQ(r.counters.fragments_stored, r.scene_fragments);
  // Truncated to 12: classes 8 and 12, the longer lists left to the truncating draw.
  RunResult truncated[2];
  int i = 0;
  for (const std::string sort : {"network", "insertion"})
    truncated[i++] =
        test::render_once("linked_list", {{"sort", sort}, {"max_per_pixel", "12"}}, "random_quads", {}, 37, 29);
  EXPECT_GT(truncated[0].counters.fragments_dropped, 0u);
  EXPECT_EQ(truncated[0].counters.fragments_dropped, truncated[1].counters.fragments_dropped);
  double worst = 0.0;
  for (size_t k = 0; k < truncated[0].image.rgba.size(); ++k)
    worst = std::max(worst, std::abs(double(truncated[0].image.rgba[k]) - double(truncated[1].image.rgba[k])));
  EXPECT_EQ(worst, 0.0) << "the classed network and the insertion sort keep different fragments";
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
    const RunResult r = test::harness().run(
        test::one_frame("linked_list", {{"sort", sort}}, "quads", {{"layers", "32"}}, 48, "shuffled:7"));
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
  // The grown pool holds the 1.25x slack: 4 heads + length (20 B/pixel) + 32 B/node + counters,
  // + the length classes 1, 8, 16, 32, 64: 5 x (16 B draw command + 4 B per 4x4 tile).
  const uint64_t nodes = uint64_t(16.0 * w * h * 1.25) + 1;
  EXPECT_EQ(r.counters.bytes_allocated, 20u * w * h + 32u * nodes + 12u + 5u * (16u + 4u * (w / 4) * (h / 4)));
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
  const RunResult r = test::harness().run(test::one_frame("linked_list", {{"sort", "bubble"}}, "quads", {}, 8));
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


const std::vector<std::string> kPoolSizings = {"previous_frame", "count", "worst_case"};
// Uneven depth complexity at 64x64: lists of 0 to 10 fragments (29 empty
// pixels, 216 single fragments, 101 lists longer than 8).
const RawParams kUnevenScene = {{"count", "64"}, {"size", "0.3"}};

const RawParams kGrouped = {{"length_classes", "true"}};

// The length classes' storage (default length_classes=true): per class a
// 16 B draw command and 4 B per 4x4 tile; max_per_pixel=64 gives classes 1, 8, 16, 32, 64.
uint64_t class_bytes(int w, int h, uint64_t classes = 5) {
  return classes * (16u + 4u * uint64_t((w + 3) / 4) * uint64_t((h + 3) / 4));
}

double work_saved(const RunResult& r, const std::string& name) {
  for (const auto& [key, value, combine] : r.counters.work_saved)
    if (key == name) return value;
  ADD_FAILURE() << "no work_saved figure " << name;
  return -1.0;
}

double largest_difference(const Image& a, const Image& b) {
  double worst = 0.0;
  for (size_t i = 0; i < a.rgba.size(); ++i) worst = std::max(worst, std::abs(double(a.rgba[i]) - double(b.rgba[i])));
  return worst;
}

TEST(LinkedListAdaptive, EveryPoolSizingAndLengthClassesMatchTheReference) {
  const std::vector<std::pair<std::string, RawParams>> scenes = {{"quads", {{"layers", "32"}}},
                                                                 {"random_quads", kUnevenScene}};
  for (const auto& [scene, scene_params] : scenes) {
    for (const std::string& sizing : kPoolSizings) {
      const RunResult grouped = test::render_once(
          "linked_list", {{"pool_sizing", sizing}, {"length_classes", "true"}}, scene, scene_params, 64, 64);
      const RunResult single = test::render_once(
          "linked_list", {{"pool_sizing", sizing}, {"length_classes", "false"}}, scene, scene_params, 64, 64);
      for (const RunResult* r : {&grouped, &single}) {
        ASSERT_TRUE(r->error.has_value()) << scene << " " << sizing;
        EXPECT_LT(r->error->max_abs, kFloatTolerance) << scene << " " << sizing;
        EXPECT_EQ(r->counters.fragments_stored, r->scene_fragments) << scene << " " << sizing;
      }
      // The same fragments in the same order and the same float blend: the classes only split the draws.
      EXPECT_LT(largest_difference(grouped.image, single.image), 1e-6) << scene << " " << sizing;
    }
  }
}

TEST(LinkedListAdaptive, CountingPassSizesThePoolExactlyFromTheFirstFrame) {
  const int w = 64, h = 64;
  for (const auto& [scene, scene_params] :
       std::vector<std::pair<std::string, RawParams>>{{"quads", {{"layers", "32"}}}, {"random_quads", kUnevenScene}}) {
    const RunResult r = test::render_once("linked_list", {{"pool_sizing", "count"}}, scene, scene_params, w, h);
    EXPECT_EQ(r.counters.overflow_retries, 0u) << scene;
    EXPECT_EQ(r.counters.passes, 2u) << scene << ": the counting pass and the fill";
    EXPECT_NE(r.stage("count", "wall"), nullptr) << scene;
    // 4 heads + length (20 B/pixel) + exactly one 32 B node per fragment + 12 B of counters + the classes.
    EXPECT_EQ(r.counters.bytes_allocated, 20u * w * h + 32u * r.scene_fragments + 12u + class_bytes(w, h)) << scene;
    EXPECT_EQ(work_saved(r, "bytes_not_allocated"), 32.0 * (64.0 * w * h - double(r.scene_fragments))) << scene;
  }
}

TEST(LinkedListAdaptive, WorstCaseAllocatesMaxPerPixelNodesPerPixelAndCountsGrowth) {
  const int w = 32, h = 32;
  const RunResult r =
      test::render_once("linked_list", {{"pool_sizing", "worst_case"}}, "quads", {{"layers", "32"}}, w, h);
  EXPECT_EQ(r.counters.bytes_allocated, 20u * w * h + 32u * 64u * w * h + 12u + class_bytes(w, h));
  EXPECT_EQ(r.counters.overflow_retries, 0u);
  EXPECT_EQ(r.counters.passes, 1u);
  EXPECT_EQ(work_saved(r, "bytes_not_allocated"), 0.0);
  // 32 layers into a worst case of 16 per pixel: the pool grows (a counted
  // re-render), the nearest 16 are composited and the rest counted as dropped.
  const RunResult grown = test::render_once("linked_list", {{"pool_sizing", "worst_case"}, {"max_per_pixel", "16"}},
                                            "quads", {{"layers", "32"}}, w, h);
  EXPECT_EQ(grown.counters.overflow_retries, 1u);
  EXPECT_EQ(grown.counters.fragments_dropped, 16u * w * h);
  // max_per_pixel=16: classes 1, 8, 16.
  EXPECT_EQ(grown.counters.bytes_allocated,
            20u * w * h + 32u * (uint64_t(32.0 * w * h * 1.25) + 1) + 12u + class_bytes(w, h, 3));
  const RunResult plain = test::render_once("linked_list", {{"pool_sizing", "worst_case"}, {"length_classes", "false"}},
                                            "quads", {{"layers", "32"}}, w, h);
  EXPECT_EQ(plain.counters.bytes_allocated, 20u * w * h + 32u * 64u * w * h + 12u);
  // previous_frame grows its first pool (1 node per pixel) to 1.25 x 32 + 1
  // nodes: 40 per pixel of the worst case's 64 allocated.
  const RunResult previous = test::render_once(
      "linked_list", {{"pool_sizing", "previous_frame"}, {"initial_nodes_per_pixel", "1"}}, "quads",
      {{"layers", "32"}}, w, h);
  EXPECT_EQ(previous.counters.overflow_retries, 1u);
  EXPECT_EQ(work_saved(previous, "bytes_not_allocated"), 32.0 * (64.0 * w * h - (40.0 * w * h + 1)));
}

TEST(LinkedListAdaptive, WorkSavedByLengthClassesOnScenesCountedByHand) {
  const int w = 32, h = 32;
  // One layer: every pixel has one fragment, all in class 1 (one full-screen
  // draw, no sort); without classes the resolve would run the 8-element
  // network (19 compare-exchanges) on each.
  const RunResult one = test::render_once("linked_list", kGrouped, "quads", {{"layers", "1"}}, w, h);
  EXPECT_LT(one.error->max_abs, kFloatTolerance);
  EXPECT_EQ(work_saved(one, "fragments_not_sorted"), double(w * h));
  EXPECT_EQ(work_saved(one, "pixels_in_short_groups"), 0.0);
  EXPECT_EQ(odd_even_merge_sort(8).size(), 19u);
  EXPECT_EQ(work_saved(one, "compare_exchanges_avoided"), 19.0 * w * h);
  // 32 layers everywhere: every pixel needs the largest array, nothing is saved.
  const RunResult full = test::render_once("linked_list", kGrouped, "quads", {{"layers", "32"}}, w, h);
  EXPECT_EQ(work_saved(full, "fragments_not_sorted"), 0.0);
  EXPECT_EQ(work_saved(full, "pixels_in_short_groups"), 0.0);
  EXPECT_EQ(work_saved(full, "compare_exchanges_avoided"), 0.0);
  // 12 layers: the frame's array is 16; every list needs it.
  const RunResult twelve = test::render_once("linked_list", kGrouped, "quads", {{"layers", "12"}}, w, h);
  EXPECT_EQ(work_saved(twelve, "pixels_in_short_groups"), 0.0);
  // Without classes nothing is saved by definition; insertion sort reports no network figure.
  const RunResult single =
      test::render_once("linked_list", {{"length_classes", "false"}}, "quads", {{"layers", "1"}}, w, h);
  EXPECT_EQ(work_saved(single, "fragments_not_sorted"), 0.0);
  EXPECT_EQ(work_saved(single, "compare_exchanges_avoided"), 0.0);
  // The classes are the network's only: the insertion sort saves nothing and needs no class storage.
  const RunResult insertion = test::render_once("linked_list", {{"sort", "insertion"}, {"length_classes", "true"}},
                                                "quads", {{"layers", "1"}}, w, h);
  EXPECT_LT(insertion.error->max_abs, kFloatTolerance);
  EXPECT_EQ(work_saved(insertion, "fragments_not_sorted"), 0.0);
  EXPECT_EQ(insertion.counters.bytes_allocated, one.counters.bytes_allocated - class_bytes(w, h));
  for (const auto& [key, value, combine] : insertion.counters.work_saved) EXPECT_NE(key, "compare_exchanges_avoided");
}

TEST(LinkedListAdaptive, WorkSavedByLengthClassesMatchesTheMeasuredListLengths) {
  const int w = 64, h = 64;
  const RunResult r = test::render_once("linked_list", kGrouped, "random_quads", kUnevenScene, w, h);
  // The harness's own per-pixel count (a separate counting shader).
  test::gl_context();
  const Scene scene = load_scene("random_quads", kUnevenScene);
  const SceneGpu gpu(scene);
  const DepthComplexity c = measure_depth_complexity(gpu, scene.camera.view, scene.camera.projection(1.0f), w, h);
  ASSERT_GE(c.max, 9u) << "the scene must need more than the smallest array";
  const uint32_t largest = std::max<uint32_t>(8, std::bit_ceil(c.max));
  // Each 4x4 tile is resolved by the smallest class (1, 8, 16, ...) that holds its longest list.
  const std::vector<uint32_t> tiles = linked_list::tile_longest(c.per_pixel, w, h);
  const auto size_of_tile = [&](uint32_t longest) {
    uint32_t size = longest <= 1 ? 1 : 8;
    while (size < longest) size *= 2;
    return size;
  };
  uint64_t not_sorted = 0, short_groups = 0, avoided = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const uint32_t length = c.per_pixel[size_t(y) * w + x];
      const uint32_t size = size_of_tile(tiles[size_t(y / 4) * (w / 4) + x / 4]);
      if (length == 1 && size == 1) ++not_sorted;
      if (length >= 2 && size < largest) ++short_groups;
      avoided += odd_even_merge_sort(largest).size() - odd_even_merge_sort(size).size();
    }
  }
  EXPECT_GT(not_sorted, 0u);
  EXPECT_GT(short_groups, 0u);
  EXPECT_EQ(work_saved(r, "fragments_not_sorted"), double(not_sorted));
  EXPECT_EQ(work_saved(r, "pixels_in_short_groups"), double(short_groups));
  EXPECT_EQ(work_saved(r, "compare_exchanges_avoided"), double(avoided));
}

TEST(LinkedList, UnknownPoolSizingIsAnErrorNamingTheParameter) {
  const RunResult r =
      test::harness().run(test::one_frame("linked_list", {{"pool_sizing", "guess"}}, "quads", {}, 8));
  EXPECT_EQ(r.status, RunStatus::error);
  EXPECT_NE(r.message.find("pool_sizing"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("guess"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace oit

// ---- storage=compact: 12-byte nodes (depth, RGBA8, next) ----------------

namespace oit {
namespace {

// packUnorm4x8 rounds each straight channel to the nearest 1/255: delta =
// 0.5/255. Front to back, C = sum T_i a_i c_i: the colour errors add up to
// at most delta (sum T_i a_i <= 1); an alpha error moves C by at most
// delta T_i per layer, and sum T_i <= 1/a for a constant alpha a. Hence
// |error| <= delta (1 + 1/a), plus delta for the composite's own rounding.
double compact_bound(double alpha) { return 0.5 / 255.0 * (2.0 + 1.0 / alpha); }

TEST(LinkedListCompact, WithinTheRgba8BoundOnThirtyTwoQuadsForEverySort) {
  for (const std::string sort : {"insertion", "selection", "network"}) {
    const RunResult compact =
        test::render_once("linked_list", {{"sort", sort}, {"storage", "compact"}}, "quads", {{"layers", "32"}}, 48, 40);
    const RunResult full = test::render_once("linked_list", {{"sort", sort}}, "quads", {{"layers", "32"}}, 48, 40);
    ASSERT_TRUE(compact.error && full.error);
    EXPECT_LE(compact.error->max_abs, compact_bound(0.3)) << sort;
    EXPECT_GT(compact.error->max_abs, full.error->max_abs) << sort << ": colours were not quantised";
    // The same fragments in 12 instead of 32 bytes a node: per pixel
    // 20 + 40 x 12 against 20 + 40 x 32 bytes (a pool of 1.25 x 32 nodes).
    EXPECT_EQ(compact.counters.fragments_stored, full.counters.fragments_stored);
    EXPECT_LT(double(compact.counters.bytes_allocated), 0.4 * double(full.counters.bytes_allocated)) << sort;
  }
}

TEST(LinkedListCompact, TruncationAndMeshesStayWithinTheBound) {
  // max_per_pixel=8 on 32 layers: the truncating draw reads compact nodes too.
  const RunResult compact = test::render_once("linked_list", {{"storage", "compact"}, {"max_per_pixel", "8"}}, "quads",
                                              {{"layers", "32"}}, 40, 32);
  const RunResult full = test::render_once("linked_list", {{"max_per_pixel", "8"}}, "quads", {{"layers", "32"}}, 40, 32);
  EXPECT_EQ(compact.counters.fragments_dropped, full.counters.fragments_dropped);
  EXPECT_LE(compare_images(compact.image, full.image).max_abs, compact_bound(0.3));
  const RunResult spheres = test::render_once("linked_list", {{"storage", "compact"}}, "spheres", {}, 48, 48);
  ASSERT_TRUE(spheres.error);
  EXPECT_LE(spheres.error->max_abs, 4.0 / 255.0);
}

}  // namespace
}  // namespace oit
