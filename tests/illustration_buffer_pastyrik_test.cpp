// illustration_buffer, pastyrik2016's parts beyond its Algorithm 2:
// sort=static_arrays (the selection sort in three static arrays of 64
// entries of its section 3.2 and Fig. 7) gives sort=array's records, and
// modulation=ray_distance follows its eq. 1 against a CPU computation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "harness/output/image.h"
#include "tests/gl_fixture.h"

namespace oit {
namespace {

constexpr double kFloatTolerance = 1e-5;  // the reference comparison of the other illustration_buffer tests

RunResult render(const RawParams& params, const std::string& scene, const RawParams& scene_params, int size) {
  return test::render_once("illustration_buffer", params, scene, scene_params, size, size);
}

// sort=static_arrays against sort=array on the same fill: the same image
// bit for bit, the same counts, and the reference's image; on stacked quads
// (also truncated to max_per_pixel, and lists longer than the 64 entries,
// which keep their 64 nearest), on a model, and on quads tied exactly in
// depth (the triangle id breaks the tie) in several submission orders.
// storage=linked is the paper's; the ranged storages read the same path.
TEST(IllustrationBufferPastyrik, StaticArraysSortGivesTheArraySortsImage) {
  struct Case {
    std::string scene;
    RawParams scene_params, params;
    int size;
    bool exact;  // within the reference tolerance (modulation=none)
  };
  const std::string ties = test::write_quads_gltf(
      "illustration_buffer_pastyrik", "ties",
      {{-1.0f, {0.9f, 0.9f, 0.1f, 0.3f}}, {-2.0f, {0.9f, 0.1f, 0.1f, 0.5f}}, {-2.0f, {0.1f, 0.9f, 0.1f, 0.5f}},
       {-1.5f, {0.2f, 0.3f, 0.9f, 0.4f}}, {-2.0f, {0.1f, 0.1f, 0.9f, 0.5f}}});
  const RawParams none = {{"modulation", "none"}};
  const std::vector<Case> cases = {
      {"quads", {{"layers", "12"}}, none, 24, true},
      {"quads", {{"layers", "12"}}, {{"modulation", "none"}, {"max_per_pixel", "5"}}, 24, false},
      {"quads", {{"layers", "70"}}, none, 8, false},  // longer than the arrays: the 64 nearest
      {"quads", {{"layers", "12"}}, {}, 24, false},  // modulated: the links follow the records
      {"model", {{"name", "elephant"}}, none, 64, true},
      {"model", {{"name", "elephant"}}, {}, 64, false},
      {ties, {}, none, 16, true}};
  for (size_t index = 0; index < cases.size(); ++index) {
    const Case& c = cases[index];
    for (const char* storage : {"linked", "linearized", "arrays"}) {
      RawParams params = c.params;
      params["storage"] = storage;
      params["sort"] = "array";
      const RunResult a = render(params, c.scene, c.scene_params, c.size);
      params["sort"] = "static_arrays";
      const RunResult s = render(params, c.scene, c.scene_params, c.size);
      const std::string what = "case " + std::to_string(index) + " (" + c.scene + ") " + storage;
      EXPECT_EQ(test::max_abs_difference(a.image, s.image), 0.0) << what;
      EXPECT_EQ(test::extra_counter(s, "static_arrays_sort"), 1.0) << what;
      EXPECT_EQ(test::extra_counter(a, "static_arrays_sort"), 0.0) << what;
      EXPECT_EQ(test::extra_counter(s, "dynamic_sort"), 0.0) << what;
      EXPECT_EQ(a.counters.fragments_stored, s.counters.fragments_stored) << what;
      EXPECT_EQ(test::extra_counter(a, "lists_truncated"), test::extra_counter(s, "lists_truncated")) << what;
      EXPECT_EQ(test::work_saved(a, "fragments_not_sorted"), test::work_saved(s, "fragments_not_sorted")) << what;
      if (c.params.count("modulation") == 0) {
        for (const char* links : {"links_left", "links_right", "links_down", "links_up"})
          EXPECT_EQ(test::extra_counter(a, links), test::extra_counter(s, links)) << what << " " << links;
      }
      if (c.exact) {
        ASSERT_TRUE(s.error.has_value()) << what;
        EXPECT_LT(s.error->max_abs, kFloatTolerance) << what;
      }
    }
  }
  // The 70 layers did reach the truncating path: every pixel's list.
  const RunResult deep = render({{"modulation", "none"}, {"sort", "static_arrays"}, {"storage", "linked"}}, "quads",
                                {{"layers", "70"}}, 8);
  EXPECT_EQ(test::extra_counter(deep, "lists_truncated"), double(8 * 8));
  // Exact ties in every submission order (the lists' order changes, the image does not).
  for (const char* order : {"reversed", "shuffled:3", "shuffled:7"}) {
    const RunResult r = test::harness().run(test::one_frame(
        "illustration_buffer", {{"modulation", "none"}, {"sort", "static_arrays"}, {"storage", "linked"}}, ties, {},
        16, order));
    ASSERT_EQ(r.status, RunStatus::ok) << order << ": " << r.message;
    ASSERT_TRUE(r.error.has_value());
    EXPECT_LT(r.error->max_abs, kFloatTolerance) << order;
  }
}

// The static arrays hold 64 entries: a longer kept list is an error naming
// the parameters and the fix.
TEST(IllustrationBufferPastyrik, StaticArraysRefuseMoreThanSixtyFourKeptFragments) {
  const RunResult r = test::harness().run(test::one_frame(
      "illustration_buffer", {{"sort", "static_arrays"}, {"max_per_pixel", "65"}}, "quads", {}, 8));
  EXPECT_EQ(r.status, RunStatus::error);
  for (const char* word : {"sort=static_arrays", "max_per_pixel=65", "max_per_pixel <= 64", "sort=array"})
    EXPECT_NE(r.message.find(word), std::string::npos) << r.message;
  const RunResult zero = test::harness().run(
      test::one_frame("illustration_buffer", {{"modulation", "ray_distance"}, {"focus_region", "0"}}, "quads", {}, 8));
  EXPECT_EQ(zero.status, RunStatus::error);
  EXPECT_NE(zero.message.find("focus_region"), std::string::npos) << zero.message;
}

// pastyrik2016 eq. 1 on the CPU: sample i (sorted nearest first) has
// opacity saturate(|d_i - d_{i+1}| / focus); the farthest, 1 (README).
std::vector<double> equation_one(std::vector<double> depths, double focus) {
  std::sort(depths.begin(), depths.end());
  std::vector<double> alpha(depths.size(), 1.0);
  for (size_t i = 0; i + 1 < depths.size(); ++i)
    alpha[i] = std::clamp(std::abs(depths[i] - depths[i + 1]) / focus, 0.0, 1.0);
  return alpha;
}

// Two quads, red in front of blue at a gap g: the pixel is (a, 0, 1 - a)
// with a the front quad's eq. 1 opacity (the back one's is 1), whatever
// the quads' own alpha; then a stack of five at uneven gaps against the
// front-to-back composite of eq. 1's opacities.
TEST(IllustrationBufferPastyrik, RayDistanceModulationFollowsEquationOne) {
  constexpr int size = 8;
  const glm::vec4 red(1.0f, 0.0f, 0.0f, 0.3f), blue(0.0f, 0.0f, 1.0f, 0.6f);
  for (const double focus : {0.5, 2.0}) {
    for (const double gap : {0.05, 0.25, 0.4, 0.5, 1.5}) {
      const std::string name = "pair_" + std::to_string(int(gap * 100));
      const std::string path = test::write_quads_gltf("illustration_buffer_pastyrik", name,
                                                      {{-1.0f, red}, {float(-1.0 - gap), blue}});
      const RunResult r = render({{"modulation", "ray_distance"}, {"focus_region", std::to_string(focus)}}, path, {},
                                 size);
      const double front = equation_one({1.0, 1.0 + gap}, focus)[0];
      const std::string what = "gap " + std::to_string(gap) + " focus " + std::to_string(focus);
      EXPECT_NEAR(r.image.at(size / 2, size / 2, 0), front, kFloatTolerance) << what;
      EXPECT_NEAR(r.image.at(size / 2, size / 2, 2), 1.0 - front, kFloatTolerance) << what;
      EXPECT_EQ(r.stage("neighbors", "wall"), nullptr);
      EXPECT_EQ(r.stage("diffuse", "wall"), nullptr);
    }
  }
  const std::vector<std::pair<float, glm::vec4>> stack = {
      {-2.0f, {0.9f, 0.2f, 0.1f, 0.3f}}, {-1.0f, {0.1f, 0.8f, 0.3f, 0.3f}}, {-4.0f, {0.2f, 0.3f, 0.9f, 0.3f}},
      {-1.25f, {0.7f, 0.7f, 0.2f, 0.3f}}, {-2.1f, {0.5f, 0.1f, 0.8f, 0.3f}}};
  const std::string path = test::write_quads_gltf("illustration_buffer_pastyrik", "stack", stack);
  const double focus = 0.5;
  std::vector<std::pair<float, glm::vec4>> sorted = stack;
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<double> depths;
  for (const auto& [z, color] : sorted) depths.push_back(-double(z));
  const std::vector<double> alpha = equation_one(depths, focus);
  const std::vector<double> by_hand = {0.5, 1.0, 0.2, 1.0, 1.0};  // gaps 0.25, 0.75, 0.1, 1.9; the last
  ASSERT_EQ(alpha.size(), by_hand.size());
  for (size_t i = 0; i < alpha.size(); ++i) EXPECT_NEAR(alpha[i], by_hand[i], 1e-6) << i;  // float depths
  glm::dvec3 expected(0.0);
  double transmittance = 1.0;
  for (size_t i = 0; i < sorted.size(); ++i) {
    expected += transmittance * alpha[i] * glm::dvec3(sorted[i].second);
    transmittance *= 1.0 - alpha[i];
  }
  for (const char* storage : {"linked", "linearized"}) {
    for (const char* order : {"original", "reversed"}) {
      const RunResult r = test::harness().run(test::one_frame(
          "illustration_buffer", {{"modulation", "ray_distance"}, {"focus_region", "0.5"}, {"storage", storage}},
          path, {}, size, order));
      ASSERT_EQ(r.status, RunStatus::ok) << r.message;
      for (int channel = 0; channel < 3; ++channel)
        EXPECT_NEAR(r.image.at(1, 2, channel), expected[channel], kFloatTolerance) << storage << " " << order;
      EXPECT_NEAR(r.image.at(1, 2, 3), 1.0 - transmittance, kFloatTolerance);
    }
  }
}

}  // namespace
}  // namespace oit
