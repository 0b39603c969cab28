// illustration_buffer: plain compositing against the reference, neighbour
// precision/recall against the parametric ground truth, the boundary
// conditions and eq. 9 against a closed-form image, pool regrowth, the
// truncation counter, parameter errors, and the work modulation=none and
// the 0/1-list sort shortcut save.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "harness/run/complexity.h"
#include "harness/output/image.h"
#include "harness/gl/context.h"
#include "tests/gl_fixture.h"
#include "scenes/scene_library.h"
#include "scenes/stacked_quads.h"

namespace oit {
namespace {

const std::vector<std::string> kSearches = {"triangle_index", "heuristic"};
constexpr double kFloatTolerance = 1e-5;

double largest_difference(const Image& a, const Image& b) {
  EXPECT_EQ(a.rgba.size(), b.rgba.size());
  double worst = 0.0;
  for (size_t i = 0; i < std::min(a.rgba.size(), b.rgba.size()); ++i)
    worst = std::max(worst, std::abs(double(a.rgba[i]) - double(b.rgba[i])));
  return worst;
}

// The illustration buffer on `scene` at w x h, once per value of parameter
// `key`, every other parameter from `params`: the runs of a switch whose
// values must give the same image.
std::vector<RunResult> render_each(const std::string& key, const std::vector<std::string>& values,
                                   const RawParams& params, const std::string& scene, const RawParams& scene_params,
                                   int w, int h) {
  std::vector<RunResult> runs;
  for (const std::string& value : values) {
    RawParams with = params;
    with[key] = value;
    runs.push_back(test::render_once("illustration_buffer", with, scene, scene_params, w, h));
  }
  return runs;
}

TEST(IllustrationBuffer, WithoutModulationEveryNeighbourModeMatchesTheReference) {
  for (const std::string& search : kSearches) {
    const RawParams params = {{"modulation", "none"}, {"neighbors", search}};
    const RunResult quads = test::render_once("illustration_buffer", params, "quads", {{"layers", "32"}}, 64, 64);
    ASSERT_TRUE(quads.error.has_value());
    EXPECT_LT(quads.error->max_abs, kFloatTolerance) << search;
    EXPECT_EQ(quads.counters.fragments_stored, 32u * 64u * 64u) << search;
    EXPECT_EQ(quads.counters.fragments_dropped, 0u) << search;
    for (const char* scene : {"spheres", "nested_spheres"}) {
      const RunResult mesh = test::render_once("illustration_buffer", params, scene, {}, 64, 64);
      ASSERT_TRUE(mesh.error.has_value());
      EXPECT_LT(mesh.error->max_abs, kFloatTolerance) << search << " on " << scene;
      EXPECT_EQ(mesh.counters.fragments_stored, mesh.scene_fragments) << search << " on " << scene;
    }
  }
}

TEST(IllustrationBuffer, FullScreenQuadsLinkEveryInteriorPairInBothModes) {
  // Every layer covers the image: each fragment has a neighbour in every
  // in-image direction, so the link counts are exact and nothing is a
  // silhouette. 1, 2, 3 and 8 layers: the triangle-index search's groups of
  // 1, 2 and 4 fragments, a group the list does not fill, and two groups.
  const int w = 24, h = 20;
  for (const int layers : {1, 2, 3, 8}) {
    for (const std::string& search : kSearches) {
      const std::string what = search + ", " + std::to_string(layers) + " layers";
      const RunResult r = test::render_once("illustration_buffer", {{"neighbors", search}}, "quads",
                                            {{"layers", std::to_string(layers)}}, w, h);
      EXPECT_EQ(test::extra_counter(r, "links_left"), double(layers * (w - 1) * h)) << what;
      EXPECT_EQ(test::extra_counter(r, "links_right"), double(layers * (w - 1) * h)) << what;
      EXPECT_EQ(test::extra_counter(r, "links_down"), double(layers * w * (h - 1))) << what;
      EXPECT_EQ(test::extra_counter(r, "links_up"), double(layers * w * (h - 1))) << what;
      EXPECT_EQ(test::extra_counter(r, "silhouette_fragments"), 0.0) << what;
      // No silhouettes, no halos, a constant alpha field: the image is plain blending.
      EXPECT_LT(r.error->max_abs, kFloatTolerance) << what;
    }
  }
}

// Precision and recall of the links against the (surface id, u, v) ground
// truth; thresholds sit below the measured values at 96x96 (see README.md).
void expect_accurate_neighbours(const std::string& scene, const RawParams& scene_params, double precision,
                                double recall) {
  for (const std::string& search : kSearches) {
    const RunResult r = test::render_once(
        "illustration_buffer", {{"neighbors", search}, {"modulation", "silhouette"}, {"measure_accuracy", "true"}},
        scene, scene_params, 96, 96);
    const double p = test::extra_counter(r, "neighbor_precision"), q = test::extra_counter(r, "neighbor_recall");
    std::printf("[ measured ] %s on %s: precision %.4f recall %.4f\n", search.c_str(), scene.c_str(), p, q);
    EXPECT_GT(p, precision) << search << " on " << scene;
    EXPECT_GT(q, recall) << search << " on " << scene;
    EXPECT_LE(p, 1.0);
    EXPECT_LE(q, 1.0);
  }
}

TEST(IllustrationBuffer, NeighbourLinksAreAccurateOnASphere) {
  expect_accurate_neighbours("nested_spheres", {{"count", "1"}}, 0.97, 0.95);
}

TEST(IllustrationBuffer, NeighbourLinksAreAccurateOnATorus) {
  expect_accurate_neighbours("torus", {}, 0.95, 0.9);
}

TEST(IllustrationBuffer, PrecisionExposesADegenerateContinuityMeasure) {
  // w_z = w_n = 0 makes every candidate of the same object equally good, so
  // Algorithm 2 takes the nearest fragment of the adjacent list: the back
  // layers of the torus link to its front layers, and precision must say so.
  const RunResult r =
      test::render_once("illustration_buffer",
                        {{"neighbors", "heuristic"},
                         {"modulation", "silhouette"},
                         {"weight_z", "0"},
                         {"weight_n", "0"},
                         {"measure_accuracy", "true"}},
                        "torus", {}, 96, 96);
  const double p = test::extra_counter(r, "neighbor_precision");
  std::printf("[ measured ] heuristic with w_z = w_n = 0 on torus: precision %.4f\n", p);
  EXPECT_LT(p, 0.9);
}

// heuristic_merge walks the depth-sorted list from the predicted depth and
// stops once the depth term alone exceeds the best measure (lists longer
// than 8: 16 layers at the centre of 8 nested spheres, 12 in 6 cylinders,
// the quads; shorter ones are scanned): exactly the
// heuristic's links (same positions in the adjacent lists) and image, for
// the default weights, a normal-dominated measure (w_n = 1000) and the
// degenerate w_z = 0 (no bound: the walk covers the whole list).
TEST(IllustrationBuffer, HeuristicMergeFindsTheHeuristicsLinks) {
  for (const auto& [scene, scene_params] :
       {std::pair{"spheres", RawParams{}}, std::pair{"nested_spheres", RawParams{{"count", "8"}}},
        std::pair{"torus", RawParams{}}, std::pair{"cylinders", RawParams{{"count", "6"}}},
        std::pair{"quads", RawParams{{"layers", "16"}, {"objects", "4"}}},
        std::pair{"quads", RawParams{{"layers", "24"}, {"objects", "1"}}}}) {
    for (const RawParams& weights : {RawParams{}, RawParams{{"weight_n", "1000"}}, RawParams{{"weight_z", "0"}}}) {
      RawParams heuristic = weights, merge = weights;
      heuristic["neighbors"] = "heuristic";
      merge["neighbors"] = "heuristic_merge";
      const RunResult a = test::render_once("illustration_buffer", heuristic, scene, scene_params, 64, 64);
      const RunResult b = test::render_once("illustration_buffer", merge, scene, scene_params, 64, 64);
      const std::string what = std::string(scene) + (weights.empty() ? "" : " " + weights.begin()->first + "=" +
                                                                              weights.begin()->second);
      EXPECT_GT(test::extra_counter(a, "links_left"), 500.0) << what;
      for (const char* name : {"links_left", "links_right", "links_down", "links_up", "link_checksum"})
        EXPECT_EQ(test::extra_counter(a, name), test::extra_counter(b, name)) << what << ": " << name;
      EXPECT_EQ(largest_difference(a.image, b.image), 0.0) << what;
    }
  }
}

// One screen-aligned quad (alpha s over black): pixels of the quad with an
// in-image neighbour pixel outside it are silhouettes (beta = 1, fixed);
// eq. 9 then gives beta = max(0, 1 - d * lambda_beta) within `iterations`
// steps, d the 4-connected distance to the silhouette. The composite is
// (s + (1 - s) beta) * colour; the colour comes from the reference (s * colour).
Image single_quad_closed_form(const Image& reference, float s, int iterations, float lambda) {
  const int w = reference.width, h = reference.height;
  auto covered = [&](int x, int y) { return reference.at(x, y, 3) > 0.5f * s; };
  std::vector<int> distance(size_t(w * h), -1);
  std::deque<std::pair<int, int>> queue;
  const int dx[4] = {-1, 1, 0, 0}, dy[4] = {0, 0, -1, 1};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!covered(x, y)) continue;
      bool silhouette = false;
      for (int d = 0; d < 4; ++d) {
        const int nx = x + dx[d], ny = y + dy[d];
        silhouette = silhouette || (nx >= 0 && ny >= 0 && nx < w && ny < h && !covered(nx, ny));
      }
      if (silhouette) {
        distance[size_t(y * w + x)] = 0;
        queue.emplace_back(x, y);
      }
    }
  while (!queue.empty()) {
    const auto [x, y] = queue.front();
    queue.pop_front();
    for (int d = 0; d < 4; ++d) {
      const int nx = x + dx[d], ny = y + dy[d];
      if (nx < 0 || ny < 0 || nx >= w || ny >= h || !covered(nx, ny) || distance[size_t(ny * w + nx)] >= 0) continue;
      distance[size_t(ny * w + nx)] = distance[size_t(y * w + x)] + 1;
      queue.emplace_back(nx, ny);
    }
  }
  Image expected = reference;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int d = distance[size_t(y * w + x)];
      if (!covered(x, y) || d < 0 || d > iterations) continue;
      const float beta = std::max(0.0f, 1.0f - float(d) * lambda);
      const float opacity = s + (1.0f - s) * beta;
      for (int c = 0; c < 3; ++c) expected.rgba[size_t((y * w + x) * 4 + c)] = reference.at(x, y, c) / s * opacity;
      expected.rgba[size_t((y * w + x) * 4 + 3)] = opacity;
    }
  return expected;
}

TEST(IllustrationBuffer, SilhouettesGetBetaOneAndEquationNinePropagatesIt) {
  const int w = 64, h = 64;
  const RawParams quad = {{"count", "1"}, {"size", "0.4"}, {"seed", "3"}};
  const Image& reference = test::harness().reference_image("random_quads", quad, w, h, glm::vec3(0.0f));
  for (const std::string& search : kSearches) {
    for (int iterations : {0, 3}) {
      for (const char* skip : {"true", "false"}) {
        const RunResult r = test::render_once("illustration_buffer",
                                              {{"neighbors", search},
                                               {"modulation", "silhouette"},
                                               {"iterations", std::to_string(iterations)},
                                               {"lambda_beta", "0.25"},
                                               {"skip_converged", skip}},
                                              "random_quads", quad, w, h);
        const Image expected = single_quad_closed_form(reference, 0.3f, iterations, 0.25f);
        EXPECT_LT(largest_difference(r.image, expected), kFloatTolerance)
            << search << " iterations " << iterations << " skip_converged " << skip;
        EXPECT_GT(test::extra_counter(r, "silhouette_fragments"), 20.0) << search;
        EXPECT_GT(r.error->max_abs, 0.5) << "silhouettes must be opaque";
      }
    }
  }
}

TEST(IllustrationBuffer, ZeroIterationsKeepTheInitialAlpha) {
  // 16 full-screen layers: no silhouettes or halos. Adaptive alpha (eq. 5)
  // gives every fragment 1 - (1 - s)^(1/16); without iterations the image is
  // that alpha composited, and the diffusion of a constant field keeps it.
  const int layers = 16, w = 32, h = 32;
  StackedQuadsParams p;
  p.layers = layers;
  const glm::dvec4 expected = composite_quad_layers(stacked_quad_layers(p), glm::vec3(0.0f), [&](double alpha) {
    return 1.0 - std::pow(1.0 - alpha, 1.0 / layers);
  });
  for (const char* iterations : {"0", "20"}) {
    const RunResult r = test::render_once(
        "illustration_buffer", {{"modulation", "silhouette_halo"}, {"adaptive_alpha", "true"}, {"iterations", iterations}},
        "quads", {{"layers", std::to_string(layers)}}, w, h);
    double worst = 0.0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(double(r.image.at(x, y, c)) - expected[c]));
    EXPECT_LT(worst, kFloatTolerance) << iterations << " iterations";
    // The coverage of adaptive alpha is s whatever the layer count (eq. 6).
    EXPECT_NEAR(expected.a, 0.3, 1e-6);
  }
}

TEST(IllustrationBuffer, DiffusionChangesTheImageOnlyWithIterations) {
  // Adaptive alpha varies with the list length on spheres: diffusion smooths it.
  const RawParams base = {{"modulation", "halo"}, {"adaptive_alpha", "true"}, {"lambda_gamma", "1"}};
  RawParams none = base, some = base, still = base;
  none["iterations"] = "0";
  some["iterations"] = "10";
  still["iterations"] = "10";
  still["lambda_alpha"] = "0";
  const RunResult a = test::render_once("illustration_buffer", none, "spheres", {}, 48, 48);
  const RunResult b = test::render_once("illustration_buffer", some, "spheres", {}, 48, 48);
  const RunResult c = test::render_once("illustration_buffer", still, "spheres", {}, 48, 48);
  EXPECT_GT(largest_difference(a.image, b.image), 1e-3);
  // lambda_alpha = 0 and lambda_gamma = 1 make every iteration the identity.
  EXPECT_LT(largest_difference(a.image, c.image), 1e-6);
}

TEST(IllustrationBuffer, ProfilesFollowEquationsTenAndEleven) {
  // Eq. 11 with p = 1 is the identity: the image without a profile. With
  // p = 0.3, and eq. 10, the fields strictly between 0 and 1 that the
  // diffusion leaves around the torus's silhouettes are remapped.
  const auto render = [](const RawParams& profile) {
    return test::render_once("illustration_buffer", profile, "torus", {}, 48, 48).image;
  };
  const auto plain = render({{"profile", "none"}});
  EXPECT_LT(largest_difference(plain, render({{"profile", "power"}, {"power_p", "1"}})), 1e-6);
  EXPECT_GT(largest_difference(plain, render({{"profile", "power"}, {"power_p", "0.3"}})), 1e-3);
  EXPECT_GT(largest_difference(plain, render({{"profile", "exponential"}})), 1e-3);
}

TEST(IllustrationBuffer, TooSmallPoolGrowsAndGivesTheSameImage) {
  const int w = 32, h = 32;
  for (const char* modulation : {"none", "silhouette_halo"}) {
    const RunResult small = test::render_once(
        "illustration_buffer", {{"modulation", modulation}, {"storage", "linked"}, {"initial_nodes_per_pixel", "1"}},
        "spheres", {}, w, h);
    const RunResult roomy = test::render_once(
        "illustration_buffer", {{"modulation", modulation}, {"storage", "linked"}, {"initial_nodes_per_pixel", "64"}},
        "spheres", {}, w, h);
    EXPECT_GE(small.counters.overflow_retries, 1u) << modulation;
    EXPECT_EQ(small.counters.passes, 2u) << modulation;
    EXPECT_EQ(roomy.counters.overflow_retries, 0u) << modulation;
    EXPECT_EQ(small.counters.fragments_stored, small.scene_fragments) << modulation;
    EXPECT_EQ(largest_difference(small.image, roomy.image), 0.0) << modulation;
  }
}

TEST(IllustrationBuffer, ListsLongerThanTheSortArrayAreCounted) {
  const int w = 16, h = 16;
  const RunResult r = test::render_once("illustration_buffer", {{"modulation", "none"}, {"max_per_pixel", "5"}}, "quads",
                                        {{"layers", "12"}}, w, h);
  EXPECT_EQ(test::extra_counter(r, "lists_truncated"), double(w * h));
  EXPECT_EQ(r.counters.fragments_dropped, 7u * w * h);
  EXPECT_EQ(r.counters.fragments_stored, 5u * w * h);
  EXPECT_GT(r.error->max_abs, 0.0);
}

TEST(IllustrationBuffer, WithoutModulationNeighboursAndStylizeAreNotDispatched) {
  const RunResult plain = test::render_once("illustration_buffer", {{"modulation", "none"}, {"iterations", "5"}},
                                            "spheres", {}, 32, 32);
  EXPECT_EQ(plain.stage("neighbors", "wall"), nullptr);
  EXPECT_EQ(plain.stage("stylize_init", "wall"), nullptr);
  EXPECT_EQ(plain.stage("diffuse", "wall"), nullptr);
  // The neighbour search, the stylize init and 5 diffusion iterations.
  EXPECT_EQ(test::work_saved(plain, "passes_skipped"), 7.0);
  EXPECT_EQ(test::extra_counter(plain, "neighbor_passes"), 0.0);
  EXPECT_EQ(test::extra_counter(plain, "stylize_passes"), 0.0);
  const RunResult styled = test::render_once("illustration_buffer", {{"iterations", "5"}}, "spheres", {}, 32, 32);
  EXPECT_NE(styled.stage("neighbors", "wall"), nullptr);
  EXPECT_NE(styled.stage("stylize_init", "wall"), nullptr);
  EXPECT_NE(styled.stage("diffuse", "wall"), nullptr);
  EXPECT_EQ(test::work_saved(styled, "passes_skipped"), 0.0);
  EXPECT_EQ(test::extra_counter(styled, "stylize_passes"), 6.0);
}

TEST(IllustrationBuffer, SingleFragmentListsSkipTheSortAndMatchTheReference) {
  const int w = 64, h = 64;
  // One layer: every list has one fragment.
  const RunResult one = test::render_once("illustration_buffer", {{"modulation", "none"}}, "quads", {{"layers", "1"}}, w, h);
  EXPECT_LT(one.error->max_abs, kFloatTolerance);
  EXPECT_EQ(test::work_saved(one, "fragments_not_sorted"), double(w * h));
  const RunResult full =
      test::render_once("illustration_buffer", {{"modulation", "none"}}, "quads", {{"layers", "32"}}, w, h);
  EXPECT_LT(full.error->max_abs, kFloatTolerance);
  EXPECT_EQ(test::work_saved(full, "fragments_not_sorted"), 0.0);
  // Truncated to one fragment per list: those lists were walked, so they count as sorted.
  const RunResult truncated = test::render_once("illustration_buffer", {{"modulation", "none"}, {"max_per_pixel", "1"}},
                                                "quads", {{"layers", "2"}}, 16, 16);
  EXPECT_EQ(truncated.counters.fragments_stored, 256u);
  EXPECT_EQ(test::work_saved(truncated, "fragments_not_sorted"), 0.0);
  // Uneven depth complexity (0 to 10 fragments per pixel), plain and stylized:
  // the shortcut and the sort feed the same records to the later stages.
  const RawParams uneven = {{"count", "64"}, {"size", "0.3"}};
  test::gl_context();
  const Scene scene = load_scene("random_quads", uneven);
  const SceneGpu gpu(scene);
  const std::vector<uint64_t> histogram =
      list_length_histogram(measure_depth_complexity(gpu, scene.camera.view, scene.camera.projection(1.0f), w, h));
  ASSERT_GT(histogram.at(0), 0u);
  ASSERT_GT(histogram.at(1), 0u);
  const RunResult plain = test::render_once("illustration_buffer", {{"modulation", "none"}}, "random_quads", uneven, w, h);
  EXPECT_LT(plain.error->max_abs, kFloatTolerance);
  EXPECT_EQ(plain.counters.fragments_stored, plain.scene_fragments);
  EXPECT_EQ(test::work_saved(plain, "fragments_not_sorted"), double(histogram[1]));
  const RunResult styled = test::render_once("illustration_buffer", {}, "random_quads", uneven, w, h);
  EXPECT_EQ(test::work_saved(styled, "fragments_not_sorted"), double(histogram[1]));
  EXPECT_EQ(styled.counters.fragments_stored, styled.scene_fragments);
}

TEST(IllustrationBuffer, InvalidParametersAreErrorsNamingTheParameter) {
  const TechniqueDescriptor& d = builtin_techniques().get("illustration_buffer");
  for (const auto& [name, value] : std::vector<std::pair<std::string, std::string>>{
           {"neighbors", "nearest"}, {"modulation", "glow"}, {"iterations", "-1"}, {"lambda_beta", "2"}}) {
    try {
      d.create(ParamSet(d.params, {{name, value}}, "technique 'illustration_buffer'"));
      ADD_FAILURE() << name << "=" << value << " was accepted";
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
    const RunResult r = test::harness().run(test::one_frame("illustration_buffer", {{name, value}}, "quads", {}, 8));
    EXPECT_EQ(r.status, RunStatus::error) << name;
    EXPECT_NE(r.message.find(name), std::string::npos) << r.message;
  }
}

}  // namespace
}  // namespace oit

namespace oit {
namespace {

using test::find_diagnostic;

TEST(IllustrationBuffer, DiagnosticImagesShowTheFrontFragmentsNeighboursOnFullScreenQuads) {
  const int w = 24, h = 16;
  for (const char* search : {"triangle_index", "heuristic"}) {
    const std::vector<DiagnosticImage> images = test::diagnostic_images_once(
        "illustration_buffer", {{"neighbors", search}}, "quads", {{"layers", "4"}}, w, h);
    const DiagnosticImage* count = find_diagnostic(images, "neighbor_count");
    const DiagnosticImage* silhouette = find_diagnostic(images, "silhouette");
    ASSERT_TRUE(count && silhouette);
    ASSERT_EQ(count->values.size(), size_t(w * h));
    EXPECT_EQ(count->low, 0.0f);
    EXPECT_EQ(count->high, 4.0f);
    int wrong = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        // Off-image directions are not counted: 3 on edges, 2 in corners.
        const float expected = 4.0f - float(x == 0) - float(x == w - 1) - float(y == 0) - float(y == h - 1);
        const size_t p = size_t(y * w + x);
        wrong += count->values[p] != expected || silhouette->values[p] != 0.0f;
      }
    EXPECT_EQ(wrong, 0) << search;
  }
}

TEST(IllustrationBuffer, DiagnosticImagesMarkSilhouettesAndEmptyPixels) {
  // A sphere: a silhouette ring of front fragments missing a neighbour,
  // linked interior, no value (NaN) outside.
  const int size = 48;
  const std::vector<DiagnosticImage> images =
      test::diagnostic_images_once("illustration_buffer", {}, "spheres", {{"count", "1"}}, size, size);
  const DiagnosticImage* count = find_diagnostic(images, "neighbor_count");
  const DiagnosticImage* silhouette = find_diagnostic(images, "silhouette");
  ASSERT_TRUE(count && silhouette);
  int empty = 0, rim = 0, interior = 0;
  for (size_t p = 0; p < count->values.size(); ++p) {
    const int x = int(p % size_t(size)), y = int(p / size_t(size));
    const float in_image = 4.0f - float(x == 0) - float(x == size - 1) - float(y == 0) - float(y == size - 1);
    if (std::isnan(count->values[p])) {
      EXPECT_TRUE(std::isnan(silhouette->values[p]));
      ++empty;
    } else if (silhouette->values[p] == 1.0f) {
      EXPECT_LT(count->values[p], in_image);
      ++rim;
    } else {
      EXPECT_EQ(count->values[p], in_image);
      ++interior;
    }
  }
  EXPECT_GT(empty, 0);
  EXPECT_GT(rim, 0);
  EXPECT_GT(interior, rim);
  // Plain blending searches no neighbours and offers nothing.
  EXPECT_TRUE(
      test::diagnostic_images_once("illustration_buffer", {{"modulation", "none"}}, "quads", {{"layers", "2"}}, 8, 8)
          .empty());
}

}  // namespace
}  // namespace oit

namespace oit {
namespace {

// skip_converged diffuses only the pixels around fragments that changed in
// the previous iteration; every skipped fragment would have recomputed its
// own value, so the image is bitwise the one of all fragments every iteration.
// (diffusion=steps: auto sweeps some of these scenes on a software rasterizer.)
TEST(IllustrationBuffer, SkippingConvergedFragmentsGivesTheSameImage) {
  struct Case {
    const char* scene;
    RawParams scene_params, params;
    bool moves = true;  // some field changes
  };
  const std::vector<Case> cases = {
      {"torus", {}, {}},
      {"spheres", {}, {{"adaptive_alpha", "true"}, {"iterations", "10"}}},
      {"random_quads", {{"count", "64"}, {"size", "0.3"}}, {{"neighbors", "heuristic"}}},
      {"nested_spheres", {}, {{"modulation", "halo"}, {"lambda_gamma", "0.2"}}},
      // Full-screen layers of four alphas: the init reads the neighbours'
      // alphas (the scene has more than one), but each links within its layer.
      {"stress_layers", {{"alpha_mode", "mixed"}, {"layers", "8"}}, {}, false}};
  for (const Case& c : cases) {
    RawParams params = c.params;
    params["diffusion"] = "steps";
    const std::vector<RunResult> runs =
        render_each("skip_converged", {"true", "false"}, params, c.scene, c.scene_params, 64, 64);
    const RunResult& fast = runs[0];
    const RunResult& full = runs[1];
    EXPECT_EQ(largest_difference(fast.image, full.image), 0.0) << c.scene;
    const double iterations = c.params.count("iterations") ? 10.0 : 20.0;
    const double all = iterations * double(fast.counters.fragments_stored);
    const double updates = test::extra_counter(fast, "fragment_updates");
    std::printf("[ measured ] %s: %.0f of %.0f fragment updates\n", c.scene, updates, all);
    EXPECT_EQ(updates > 0.0, c.moves) << c.scene;
    EXPECT_LT(updates, all) << c.scene;
    EXPECT_EQ(test::work_saved(fast, "fragment_updates_skipped"), all - updates) << c.scene;
    EXPECT_EQ(find_figure(full.counters.extra, "fragment_updates"), std::nullopt) << c.scene;
  }
}

TEST(IllustrationBuffer, ConvergedFullScreenLayersAreNeverDiffused) {
  // Full layers: no silhouette, no halo, one alpha. The init queues no
  // pixel (no linked neighbour starts with another value), so none of the
  // 20 steps updates a fragment; the image is plain blending, and the one
  // of every fragment every step.
  const int w = 32, h = 24;
  for (const char* diffusion : {"steps", "sweep"}) {
    const RunResult r = test::render_once("illustration_buffer", {{"diffusion", diffusion}}, "quads", {{"layers", "8"}}, w, h);
    EXPECT_EQ(test::extra_counter(r, "fragment_updates"), 0.0) << diffusion;
    EXPECT_EQ(test::work_saved(r, "fragment_updates_skipped"), 20.0 * 8 * w * h) << diffusion;
    EXPECT_LT(r.error->max_abs, kFloatTolerance) << diffusion;
    const RunResult full = test::render_once("illustration_buffer", {{"diffusion", "steps"}, {"skip_converged", "false"}},
                                             "quads", {{"layers", "8"}}, w, h);
    EXPECT_EQ(largest_difference(r.image, full.image), 0.0) << diffusion;
  }
  // The sweeps see no seed in the init and run no round.
  const RunResult swept = test::render_once("illustration_buffer", {{"diffusion", "sweep"}}, "quads", {{"layers", "8"}}, w, h);
  EXPECT_EQ(test::extra_counter(swept, "sweep_rounds"), 0.0);
}

TEST(IllustrationBuffer, ADiffusionToleranceStaysWithinItsMeasuredError) {
  // Adaptive alpha on spheres keeps moving by float rounding for many
  // iterations; a tolerance stops the small moves (README: the measured error).
  const RawParams base = {
      {"adaptive_alpha", "true"}, {"modulation", "halo"}, {"iterations", "50"}, {"diffusion", "steps"}};
  RawParams loose = base, exact = base, full = base;
  loose["diffusion_tolerance"] = "0.0001";
  full["skip_converged"] = "false";
  const RunResult a = test::render_once("illustration_buffer", loose, "spheres", {}, 64, 64);
  const RunResult b = test::render_once("illustration_buffer", exact, "spheres", {}, 64, 64);
  const RunResult c = test::render_once("illustration_buffer", full, "spheres", {}, 64, 64);
  EXPECT_EQ(largest_difference(b.image, c.image), 0.0);
  const double error = largest_difference(a.image, c.image);
  std::printf("[ measured ] tolerance 0.0001: max image difference %.6f, updates %.0f vs %.0f\n", error,
              test::extra_counter(a, "fragment_updates"), test::extra_counter(b, "fragment_updates"));
  EXPECT_LT(error, 2e-3);  // measured 6.5e-4 (README)
  EXPECT_LT(test::extra_counter(a, "fragment_updates"), test::extra_counter(b, "fragment_updates"));
}

// diffusion=sweep: in-place sweeps along the rows until nothing moves, the
// fixed point of eq. 9, which is the result of the `iterations` steps where
// alpha cannot move and the steps carry beta and gamma from 1 to 0.
TEST(IllustrationBuffer, SweepingToTheFixedPointGivesTheStepsImage) {
  struct Case {
    const char* scene;
    RawParams scene_params, params;
  };
  const RawParams quads = {{"count", "64"}, {"size", "0.3"}};
  const std::vector<Case> cases = {
      {"torus", {}, {}},
      {"spheres", {}, {}},
      {"nested_spheres", {}, {{"modulation", "halo"}, {"lambda_gamma", "0.2"}}},
      {"random_quads", quads, {{"neighbors", "heuristic"}}},
      // In float, 1 - 0.1 nine times is 0.09999993 and ten times -7e-8: 9
      // steps are the fewest after which a 10th step would add nothing.
      {"random_quads", quads, {{"modulation", "silhouette"}, {"lambda_beta", "0.1"}, {"iterations", "9"}}}};
  for (const Case& c : cases) {
    RawParams steps = c.params, sweep = c.params;
    steps["diffusion"] = "steps";
    steps["skip_converged"] = "false";
    sweep["diffusion"] = "sweep";
    const RunResult a = test::render_once("illustration_buffer", steps, c.scene, c.scene_params, 64, 64);
    const RunResult b = test::render_once("illustration_buffer", sweep, c.scene, c.scene_params, 64, 64);
    ASSERT_EQ(b.status, RunStatus::ok) << c.scene << ": " << b.message;
    EXPECT_EQ(largest_difference(a.image, b.image), 0.0) << c.scene;
    EXPECT_EQ(test::extra_counter(b, "sweep_diffusion"), 1.0) << c.scene;
    EXPECT_EQ(test::extra_counter(a, "sweep_diffusion"), 0.0) << c.scene;
    const double rounds = test::extra_counter(b, "sweep_rounds");
    std::printf("[ measured ] %s: %.0f sweep rounds\n", c.scene, rounds);
    EXPECT_GE(rounds, 1.0) << c.scene;
    // A round: four sweeps and a check, each over every fragment once.
    EXPECT_EQ(test::extra_counter(b, "fragment_updates"), 5.0 * rounds * double(b.counters.fragments_stored)) << c.scene;
  }
}

// Where the fixed point is not the steps' result, sweep is an error naming
// why, and auto runs the steps.
TEST(IllustrationBuffer, SweepingWhereTheFixedPointDiffersIsAnErrorAndAutoSteps) {
  test::gl_context();
  const double software = test::gl_context().device().software ? 1.0 : 0.0;
  const RawParams quads = {{"count", "64"}, {"size", "0.3"}};
  struct Case {
    const char* scene;
    RawParams scene_params, params;
    std::string named;
  };
  for (const Case& c : std::vector<Case>{
           {"spheres", {}, {{"adaptive_alpha", "true"}}, "adaptive_alpha"},
           // 8 steps leave 0 at distance 9, where the fixed point has 0.09999993.
           {"random_quads", quads, {{"modulation", "silhouette"}, {"lambda_beta", "0.1"}, {"iterations", "8"}}, "iterations"},
           {"stress_layers", {{"alpha_mode", "mixed"}, {"layers", "4"}}, {}, "one alpha"},
           // A tolerance asks for the steps that stop small moves.
           {"torus", {}, {{"diffusion_tolerance", "0.01"}}, "diffusion_tolerance"}}) {
    RawParams sweep = c.params, automatic = c.params, steps = c.params;
    sweep["diffusion"] = "sweep";
    steps["diffusion"] = "steps";
    const RunResult r = test::harness().run(test::one_frame("illustration_buffer", sweep, c.scene, c.scene_params, 32));
    EXPECT_EQ(r.status, RunStatus::error) << c.named;
    EXPECT_NE(r.message.find(c.named), std::string::npos) << r.message;
    const RunResult a = test::render_once("illustration_buffer", automatic, c.scene, c.scene_params, 32, 32);
    const RunResult b = test::render_once("illustration_buffer", steps, c.scene, c.scene_params, 32, 32);
    ASSERT_EQ(a.status, RunStatus::ok) << c.named << ": " << a.message;
    EXPECT_EQ(test::extra_counter(a, "sweep_diffusion"), 0.0) << c.named;
    EXPECT_EQ(largest_difference(a.image, b.image), 0.0) << c.named;
  }
  // Where it is exact, auto sweeps on a software rasterizer and steps on a GPU.
  const RunResult torus = test::render_once("illustration_buffer", {}, "torus", {}, 32, 32);
  EXPECT_EQ(test::extra_counter(torus, "sweep_diffusion"), software);
}

TEST(IllustrationBuffer, OneIterationTimesInitialisationAndTheStepApart) {
  const RunResult r = test::render_once("illustration_buffer", {{"iterations", "1"}}, "torus", {}, 32, 32);
  // count: storage=linearized's counting pass (storage=auto's on software GL);
  // storage=linked (auto on a GPU) clears instead.
  const bool linearized = test::extra_counter(r, "linearized_storage") == 1.0;
  for (const char* stage : {linearized ? "count" : "clear", "fill", "sort", "neighbors", "stylize_init", "diffuse",
                            "compose"})
    EXPECT_NE(r.stage(stage, "wall"), nullptr) << stage;
  EXPECT_EQ(r.stage(linearized ? "clear" : "count", "wall"), nullptr);
  EXPECT_EQ(r.stage("stylize", "wall"), nullptr);
  EXPECT_EQ(test::extra_counter(r, "stylize_passes"), 2.0);
  // measure_accuracy is off unless asked for: no truth records, no precision.
  EXPECT_EQ(find_figure(r.counters.extra, "neighbor_precision"), std::nullopt);
  const RunResult measured =
      test::render_once("illustration_buffer", {{"iterations", "1"}, {"measure_accuracy", "true"}}, "torus", {}, 32, 32);
  EXPECT_TRUE(find_figure(measured.counters.extra, "neighbor_precision").has_value());
  // 16 B per pool record more.
  EXPECT_EQ((measured.counters.bytes_allocated - r.counters.bytes_allocated) % 16, 0u);
  EXPECT_GT(measured.counters.bytes_allocated, r.counters.bytes_allocated);
}

// pastyrik2016 Algorithm 2 sorts the lists in the buffers; it must give the
// records (so the image, the counts and the links) of the array sort.
TEST(IllustrationBuffer, DynamicSortGivesTheArraySortsImage) {
  struct Case {
    const char* scene;
    RawParams scene_params, params;
  };
  const std::vector<Case> cases = {{"spheres", {}, {}},
                                   {"random_quads", {{"count", "64"}, {"size", "0.3"}}, {{"modulation", "none"}}},
                                   {"quads", {{"layers", "12"}}, {{"max_per_pixel", "5"}, {"modulation", "none"}}},
                                   {"torus", {}, {{"neighbors", "heuristic"}}}};
  for (const Case& c : cases) {
    RawParams linked = c.params;
    linked["storage"] = "linked";  // sort=dynamic sorts the fill's linked lists
    const std::vector<RunResult> runs =
        render_each("sort", {"array", "dynamic", "auto"}, linked, c.scene, c.scene_params, 48, 48);
    const RunResult& a = runs[0];
    const RunResult& d = runs[1];
    const RunResult& x = runs[2];
    EXPECT_EQ(largest_difference(a.image, d.image), 0.0) << c.scene;
    EXPECT_EQ(largest_difference(a.image, x.image), 0.0) << c.scene;
    EXPECT_EQ(test::extra_counter(a, "dynamic_sort"), 0.0) << c.scene;
    EXPECT_EQ(test::extra_counter(d, "dynamic_sort"), 1.0) << c.scene;
    // auto: the dynamic sort for lists of at most 4 fragments (the torus), else the array.
    EXPECT_EQ(test::extra_counter(x, "dynamic_sort"), x.max_depth_complexity <= 4 ? 1.0 : 0.0) << c.scene;
    EXPECT_EQ(a.counters.fragments_stored, d.counters.fragments_stored) << c.scene;
    EXPECT_EQ(a.counters.fragments_dropped, d.counters.fragments_dropped) << c.scene;
    EXPECT_EQ(test::extra_counter(a, "lists_truncated"), test::extra_counter(d, "lists_truncated")) << c.scene;
    EXPECT_EQ(test::work_saved(a, "fragments_not_sorted"),
              test::work_saved(d, "fragments_not_sorted"))
        << c.scene;
    if (c.params.count("modulation") == 0) {
      for (const char* links : {"links_left", "links_right", "links_down", "links_up"})
        EXPECT_EQ(test::extra_counter(a, links), test::extra_counter(d, links)) << c.scene << " " << links;
    }
  }
  const RunResult plain = test::render_once(
      "illustration_buffer", {{"sort", "dynamic"}, {"storage", "linked"}, {"modulation", "none"}}, "spheres", {}, 48, 48);
  EXPECT_LT(plain.error->max_abs, kFloatTolerance);
}

// storage=linearized (a counting pass, each pixel's contiguous range from
// the prefix sum, filled in place) and storage=arrays (no counting pass:
// per-pixel arrays, filled again with more slots when a list is longer)
// must give the records of the linked lists: the same image, counts and
// links, with both ways of taking a slot, also with truncated lists.
// linearized is exactly sized, so never re-grows; arrays start with
// initial_nodes_per_pixel = 8 slots, so the 12 quad layers grow them once.
// Their sort and search run over the covered pixels only, the linked
// lists' over all.
TEST(IllustrationBuffer, LinearizedAndArrayStorageGiveTheLinkedListsRecords) {
  struct Case {
    const char* scene;
    RawParams scene_params, params;
  };
  const std::vector<Case> cases = {{"spheres", {}, {}},
                                   {"torus", {}, {}},
                                   {"torus", {}, {{"neighbors", "heuristic"}}},
                                   {"random_quads", {{"count", "64"}, {"size", "0.3"}}, {{"modulation", "none"}}},
                                   {"quads", {{"layers", "12"}}, {{"max_per_pixel", "5"}, {"modulation", "none"}}},
                                   {"quads", {{"layers", "12"}, {"objects", "3"}}, {{"max_per_pixel", "5"}}}};
  for (const Case& c : cases) {
    RawParams linked = c.params;
    linked["storage"] = "linked";
    const RunResult l = test::render_once("illustration_buffer", linked, c.scene, c.scene_params, 48, 40);
    for (const char* storage : {"linearized", "arrays"}) {
      for (const char* fill : {"auto", "atomic"}) {
        RawParams ranged = c.params;
        ranged["storage"] = storage;
        ranged["fill"] = fill;
        const RunResult r = test::render_once("illustration_buffer", ranged, c.scene, c.scene_params, 48, 40);
        const std::string what = std::string(c.scene) + " storage=" + storage + " fill=" + fill;
        ASSERT_EQ(r.status, RunStatus::ok) << what << ": " << r.message;
        EXPECT_EQ(largest_difference(l.image, r.image), 0.0) << what;
        const bool arrays = std::string(storage) == "arrays";
        EXPECT_EQ(test::extra_counter(r, "linearized_storage"), arrays ? 0.0 : 1.0) << what;
        EXPECT_EQ(test::extra_counter(r, "array_storage"), arrays ? 1.0 : 0.0) << what;
        if (std::string(fill) == "atomic") {
          EXPECT_EQ(test::extra_counter(r, "framebuffer_fetch_fill"), 0.0) << what;
        }
        if (arrays) {
          const uint64_t regrown = r.max_depth_complexity > 8 ? 1 : 0;
          EXPECT_EQ(r.counters.overflow_retries, regrown) << what;
          EXPECT_EQ(r.counters.passes, 1 + regrown) << what;  // the fill, again after a regrowth
        } else {
          EXPECT_EQ(r.counters.overflow_retries, 0u) << what;
          EXPECT_EQ(r.counters.passes, 2u) << what;  // the counting pass and the fill
          EXPECT_LT(r.counters.bytes_allocated, l.counters.bytes_allocated) << what;
        }
        EXPECT_EQ(r.counters.fragments_stored, l.counters.fragments_stored) << what;
        EXPECT_EQ(r.counters.fragments_dropped, l.counters.fragments_dropped) << what;
        EXPECT_EQ(test::work_saved(r, "fragments_not_sorted"), test::work_saved(l, "fragments_not_sorted")) << what;
        // The sort and the search ran over the covered pixels only (the
        // torus leaves its hole empty, the full-screen quads nothing).
        EXPECT_EQ(test::work_saved(l, "empty_pixels_not_dispatched"), 0.0) << what;
        const double empty = test::work_saved(r, "empty_pixels_not_dispatched");
        if (std::string(c.scene) == "torus") {
          EXPECT_GT(empty, 0.0) << what;
        } else if (std::string(c.scene) == "quads") {
          EXPECT_EQ(empty, 0.0) << what;
        }
        for (const char* counter : {"lists_truncated", "links_left", "links_right", "links_down", "links_up",
                                    "link_checksum", "silhouette_fragments", "fragment_updates"}) {
          const bool counted = find_figure(l.counters.extra, counter).has_value();
          EXPECT_EQ(find_figure(r.counters.extra, counter).has_value(), counted) << what << " " << counter;
          if (counted) {
            EXPECT_EQ(test::extra_counter(r, counter), test::extra_counter(l, counter)) << what << " " << counter;
          }
        }
      }
    }
  }
}

// flat_color_records: on unlit scenes the fill stores no colour and the sort
// fetches the triangle's; on lit ones too with contiguous ranges, whose
// record keeps the light factor instead of a list link (the linked lists'
// lit records keep their colour). The records, and so the image, are the
// same, bit for bit.
TEST(IllustrationBuffer, FlatColourRecordsGiveTheStoredColoursImage) {
  struct Case {
    const char* scene;
    RawParams scene_params, params;
    double flat;  // whether the fill left the colour out (an unlit scene, or a lit one with contiguous ranges)
  };
  const std::vector<Case> cases = {
      {"quads", {{"layers", "12"}, {"objects", "3"}}, {}, 1.0},
      {"random_quads", {{"count", "64"}, {"size", "0.3"}}, {{"modulation", "none"}}, 1.0},
      {"quads", {{"layers", "12"}}, {{"modulation", "angle"}, {"storage", "linked"}}, 1.0},
      {"quads", {{"layers", "6"}}, {{"neighbors", "heuristic"}, {"max_per_pixel", "4"}}, 1.0},
      {"torus", {}, {{"storage", "linked"}}, 0.0},
      {"torus", {}, {{"storage", "linearized"}}, 1.0},
      {"torus", {}, {{"storage", "arrays"}}, 1.0},
      {"nested_spheres", {}, {{"storage", "arrays"}, {"modulation", "none"}}, 1.0}};
  for (const Case& c : cases) {
    const std::vector<RunResult> runs =
        render_each("flat_color_records", {"false", "true"}, c.params, c.scene, c.scene_params, 40, 32);
    const RunResult& a = runs[0];
    const RunResult& b = runs[1];
    EXPECT_EQ(largest_difference(a.image, b.image), 0.0) << c.scene;
    EXPECT_EQ(test::extra_counter(a, "flat_color_records"), 0.0) << c.scene;
    EXPECT_EQ(test::extra_counter(b, "flat_color_records"), c.flat) << c.scene;
    if (c.params.count("modulation") == 0) {
      EXPECT_EQ(test::extra_counter(a, "link_checksum"), test::extra_counter(b, "link_checksum")) << c.scene;
    }
  }
  const RunResult plain = test::render_once("illustration_buffer", {{"modulation", "none"}}, "quads", {{"layers", "8"}}, 24, 24);
  EXPECT_EQ(test::extra_counter(plain, "flat_color_records"), 1.0);
  EXPECT_LT(plain.error->max_abs, kFloatTolerance);
}

TEST(IllustrationBuffer, StorageOptionsThatDoNotGoTogetherAreErrorsNamingThem) {
  const TechniqueDescriptor& d = builtin_techniques().get("illustration_buffer");
  for (const auto& [params, named] : std::vector<std::pair<RawParams, std::string>>{
           {{{"storage", "linearized"}, {"sort", "dynamic"}}, "sort=dynamic"},
           {{{"storage", "arrays"}, {"sort", "dynamic"}}, "sort=dynamic"},
           {{{"storage", "linked"}, {"fill", "atomic"}}, "fill=atomic"}}) {
    const RunResult r = test::harness().run(test::one_frame("illustration_buffer", params, "quads", {}, 8));
    EXPECT_EQ(r.status, RunStatus::error) << named;
    EXPECT_NE(r.message.find(named), std::string::npos) << r.message;
    // Built directly, with the `auto`s the harness would resolve given.
    RawParams resolved = params;
    resolved.insert({{"diffusion", "steps"}, {"flat_color_records", "false"}});
    EXPECT_THROW(d.create(ParamSet(d.params, resolved, "technique 'illustration_buffer'")), std::invalid_argument)
        << named;
  }
}

// storage=auto: linearized on a software rasterizer's first frame (later
// ones may fill arrays: the test below), linked on a GPU (the counter says
// which ran); an explicit sort=dynamic or fill= decides it.
TEST(IllustrationBuffer, AutoStorageFollowsTheDeviceUnlessSortOrFillNeedsOne) {
  test::gl_context();
  const double software = test::gl_context().device().software ? 1.0 : 0.0;
  for (const auto& [params, linearized, what] : std::vector<std::tuple<RawParams, double, std::string>>{
           {{}, software, "defaults"},
           {{{"sort", "dynamic"}}, 0.0, "sort=dynamic"},
           {{{"fill", "atomic"}}, 1.0, "fill=atomic"}}) {
    const RunResult r = test::harness().run(test::one_frame("illustration_buffer", params, "quads", {}, 8));
    ASSERT_EQ(r.status, RunStatus::ok) << what << ": " << r.message;
    EXPECT_EQ(test::extra_counter(r, "linearized_storage"), linearized) << what;
  }
}

// storage=auto on a software rasterizer: the counting pass on a tile's
// first frame, then per-pixel arrays on the frames after one whose slots
// (pixels x longest list) held at most 4x its fragments: the torus's even
// lists, not the spheres' (a deep middle, empty corners). On a GPU: linked
// lists. The image is the linked lists' either way.
TEST(IllustrationBuffer, AutoStorageFillsArraysAfterAFrameOfEvenLists) {
  test::gl_context();
  const bool software = test::gl_context().device().software;
  for (const char* scene : {"torus", "spheres"}) {
    RunSpec spec = test::one_frame("illustration_buffer", {}, scene, {}, 48);
    spec.warmup = 1;
    spec.frames = 2;
    const RunResult r = test::harness().run(spec);
    ASSERT_EQ(r.status, RunStatus::ok) << scene << ": " << r.message;
    const bool even = uint64_t(48 * 48) * r.max_depth_complexity <= 4 * r.scene_fragments;
    EXPECT_EQ(even, std::string(scene) == "torus") << scene;  // both branches are covered
    const bool arrays = software && even;
    EXPECT_EQ(test::extra_counter(r, "array_storage"), arrays ? 1.0 : 0.0) << scene;
    EXPECT_EQ(test::extra_counter(r, "linearized_storage"), software && !even ? 1.0 : 0.0) << scene;
    if (software) {
      EXPECT_EQ(r.counters.passes, arrays ? 1u : 2u) << scene;  // no counting pass in an arrays frame
    }
    const RunResult linked =
        test::render_once("illustration_buffer", {{"storage", "linked"}}, scene, {}, 48, 48);
    EXPECT_EQ(largest_difference(linked.image, r.image), 0.0) << scene;
  }
}

// The technique with its defaults, every `auto` resolved for this device
// and `scene` as the harness resolves them (TechniqueDescriptor::resolve),
// rendering 48 x 48 frames one after another (test::TechniqueRenderer
// builds the defaults unresolved).
struct ResolvedRenderer {
  static constexpr int kSize = 48;
  std::unique_ptr<Technique> technique;
  RenderTarget target{kSize, kSize};
  StageClock clock{ClockKind::wall};

  ResolvedRenderer(const TechniqueDescriptor& d, const Scene& scene) {
    const RawParams given;
    const ParamSet requested(d.params, given, "technique '" + d.id + "'");
    const FrameContent content{kSize, kSize};
    RawParams resolved;
    for (const auto& [key, value] : d.resolve(
             requested, {test::gl_context().device(), {scene.triangle_count(), scene.object_count, true}, content, given}))
      resolved[key] = value;
    technique = d.create(ParamSet(d.params, resolved, "technique '" + d.id + "'"));
    technique->resize(kSize, kSize);
  }
  Image render(const SceneGpu& gpu) {
    const Camera& camera = gpu.scene().camera;
    const Frame frame{gpu, camera.view, camera.projection(1.0f), kSize, kSize, glm::vec3(0.0f), target.framebuffer.id(),
                      clock};
    render_frame(*technique, frame, false, true);
    return read_texture_rgba32f(target.color.id(), kSize, kSize);
  }
};

// storage=auto on a software rasterizer, when a frame's lists outgrow the
// slots the last frame's even lists sized (the torus's, then the nested
// spheres' six layers): that frame is filled again into exact ranges from
// the counts its cursors hold (an overflow retry, two passes, no counting
// pass, no arrays sized by an uneven frame), with the image a first frame
// of exact ranges gives.
TEST(IllustrationBuffer, AutoStorageRefillsIntoExactRangesWhenAListOutgrowsItsSlots) {
  test::gl_context();
  const TechniqueDescriptor& d = builtin_techniques().get("illustration_buffer");
  const Scene torus = load_scene("torus", {}), nested = load_scene("nested_spheres", {});
  const SceneGpu torus_gpu(torus), nested_gpu(nested);
  ResolvedRenderer moved(d, torus), fresh(d, torus);
  moved.render(torus_gpu);  // the counting pass: even lists
  moved.render(torus_gpu);  // per-pixel arrays of the torus's longest list
  const double arrays_before = find_figure(moved.technique->counters().extra, "array_storage").value_or(-1.0);
  const Image image = moved.render(nested_gpu);
  const TechniqueCounters c = moved.technique->counters();
  if (test::gl_context().device().software) {
    EXPECT_EQ(arrays_before, 1.0);
    EXPECT_EQ(c.overflow_retries, 1u);
    EXPECT_EQ(c.passes, 2u);  // the fill into arrays, then into exact ranges
    EXPECT_EQ(find_figure(c.extra, "array_storage").value_or(-1.0), 0.0);
    EXPECT_EQ(find_figure(c.extra, "linearized_storage").value_or(-1.0), 1.0);
  }
  EXPECT_EQ(largest_difference(fresh.render(nested_gpu), image), 0.0);
  // The next frame of the nested spheres takes arrays of their longest list.
  const Image again = moved.render(nested_gpu);
  EXPECT_EQ(largest_difference(again, image), 0.0);
  if (test::gl_context().device().software) {
    EXPECT_EQ(find_figure(moved.technique->counters().extra, "array_storage").value_or(-1.0), 1.0);
  }
}

// carnecky2013 Fig. 11(c): opacity = (2/pi) * the angle between normal and
// view ray. A sphere of radius R met by a ray at distance h from its centre
// is entered and left at the same angle, asin(h / R), so a pixel's coverage
// is 1 - (1 - a)^2 with a = (2/pi) asin(h / R).
TEST(IllustrationBuffer, AngleBasedOpacityFollowsTheSpheresClosedForm) {
  const int size = 64;
  const RawParams sphere = {{"count", "1"}, {"slices", "256"}, {"stacks", "128"}};
  const RunResult r = test::render_once("illustration_buffer", {{"modulation", "angle"}}, "nested_spheres", sphere,
                                        size, size);
  EXPECT_EQ(r.stage("neighbors", "wall"), nullptr);
  EXPECT_EQ(r.stage("diffuse", "wall"), nullptr);
  const Scene scene = load_scene("nested_spheres", sphere);
  ASSERT_FALSE(scene.camera.orthographic);
  const glm::mat4 projection = scene.camera.projection(1.0f);
  const glm::vec3 centre = glm::vec3(scene.camera.view * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  const double radius = 1.0, pi = 3.14159265358979;
  double worst = 0.0;
  int inside = 0, outside_nonzero = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double nx = (x + 0.5) / size * 2.0 - 1.0, ny = (y + 0.5) / size * 2.0 - 1.0;
      const glm::dvec3 ray = glm::normalize(glm::dvec3((nx + projection[2][0]) / projection[0][0],
                                                       (ny + projection[2][1]) / projection[1][1], -1.0));
      const glm::dvec3 c(centre);
      const double h = glm::length(c - glm::dot(c, ray) * ray);
      const float coverage = r.image.at(x, y, 3);
      if (h > 1.05 * radius) {
        outside_nonzero += coverage != 0.0f;
      } else if (h < 0.9 * radius) {
        const double a = 2.0 / pi * std::asin(h / radius);
        worst = std::max(worst, std::abs(double(coverage) - (1.0 - (1.0 - a) * (1.0 - a))));
        ++inside;
      }
    }
  std::printf("[ measured ] angle-based coverage vs closed form: max difference %.5f over %d pixels\n", worst, inside);
  EXPECT_GT(inside, 500);
  EXPECT_EQ(outside_nonzero, 0);
  EXPECT_LT(worst, 1e-3);  // the mesh's interpolated normals against the exact sphere (measured 1.4e-4)
  // Full-screen quads face an orthographic camera: angle 0, fully transparent
  // (the paper's flat cube); the image is the black background.
  const RunResult flat = test::render_once("illustration_buffer", {{"modulation", "angle"}}, "quads", {{"layers", "4"}}, 16, 16);
  EXPECT_EQ(*std::max_element(flat.image.rgba.begin(), flat.image.rgba.end()), 0.0f);
}

// carnecky2013 Fig. 11(d): opacity = min(1, scale |grad n|). Flat quads have
// a constant normal, hence nothing at all; on a sphere the normal turns
// faster per pixel towards the rim, so the coverage grows outwards.
TEST(IllustrationBuffer, NormalVariationOpacityIsZeroOnFlatLayersAndGrowsTowardsASpheresRim) {
  const RunResult flat =
      test::render_once("illustration_buffer", {{"modulation", "normal_variation"}}, "quads", {{"layers", "4"}}, 16, 16);
  EXPECT_EQ(*std::max_element(flat.image.rgba.begin(), flat.image.rgba.end()), 0.0f);
  EXPECT_EQ(flat.stage("neighbors", "wall"), nullptr);
  const int size = 64;
  const RawParams sphere = {{"count", "1"}, {"slices", "256"}, {"stacks", "128"}};
  const RunResult r = test::render_once("illustration_buffer",
                                        {{"modulation", "normal_variation"}, {"normal_variation_scale", "2"}},
                                        "nested_spheres", sphere, size, size);
  // Coverage along the middle row from the centre outwards, until the sphere ends.
  std::vector<float> row;
  for (int x = size / 2; x < size && r.image.at(x, size / 2, 3) > 0.0f; ++x) row.push_back(r.image.at(x, size / 2, 3));
  ASSERT_GT(row.size(), 8u);
  std::printf("[ measured ] normal variation coverage from the centre outwards:");
  for (float v : row) std::printf(" %.3f", v);
  std::printf("\n");
  EXPECT_GT(row.front(), 0.0f);
  int decreasing = 0;
  for (size_t i = 1; i + 1 < row.size(); ++i) decreasing += row[i] < row[i - 1] - 1e-3f;
  EXPECT_EQ(decreasing, 0);
  EXPECT_GT(row.back(), 1.5f * row.front());
  // At the centre the ray meets the sphere (radius 1, centre at eye depth d)
  // head-on at depths d -+ 1; there the normal turns by one radian per unit
  // of length in x and in y, and one pixel spans z * 2 / (P00 * size), so
  // |grad n| = sqrt(2) z * 2 / (P00 * size) for each of the two layers.
  const Scene scene = load_scene("nested_spheres", sphere);
  const double p00 = scene.camera.projection(1.0f)[0][0];
  const double d = -(scene.camera.view * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)).z;
  auto layer = [&](double z) { return std::min(1.0, 2.0 * std::sqrt(2.0) * z * 2.0 / (p00 * size)); };
  const double centre = 1.0 - (1.0 - layer(d - 1.0)) * (1.0 - layer(d + 1.0));
  std::printf("[ measured ] centre coverage %.4f, closed form %.4f\n", row.front(), centre);
  EXPECT_NEAR(row.front(), centre, 0.02 * centre);
  // Scale 0: nothing is drawn.
  const RunResult none = test::render_once("illustration_buffer",
                                           {{"modulation", "normal_variation"}, {"normal_variation_scale", "0"}},
                                           "nested_spheres", sphere, 16, 16);
  EXPECT_EQ(*std::max_element(none.image.rgba.begin(), none.image.rgba.end()), 0.0f);
}

// The parameters a run used (RunResult::technique_params: "key=value ...").
RawParams used_params(const RunResult& r) {
  RawParams params;
  std::istringstream words(r.technique_params);
  for (std::string word; words >> word;) {
    const size_t equals = word.find('=');
    if (equals != std::string::npos) params[word.substr(0, equals)] = word.substr(equals + 1);
  }
  return params;
}

// preset=paper: every parameter the user leaves out at carnecky2013's
// published value (README: Preset), the image of giving those values by
// hand, and explicit parameters over the preset.
TEST(IllustrationBuffer, PaperPresetResolvesToThePublishedValuesAndTheirImage) {
  test::gl_context();
  const RawParams paper = {{"neighbors", "heuristic"},   {"modulation", "silhouette_halo"},
                           {"adaptive_alpha", "false"},  {"iterations", "20"},
                           {"lambda_alpha", "1"},        {"lambda_beta", "0.05"},
                           {"lambda_gamma", "0.1"},      {"profile", "none"},
                           {"weight_z", "1"},            {"weight_n", "1"},
                           {"storage", "linked"},        {"sort", "array"},
                           {"diffusion", "steps"},       {"skip_converged", "false"},
                           {"diffusion_tolerance", "0"}, {"flat_color_records", "false"},
                           {"field_diffusion", "nonphysical"}};
  const RunResult preset =
      test::harness().run(test::one_frame("illustration_buffer", {{"preset", "paper"}}, "torus", {}, 32));
  ASSERT_EQ(preset.status, RunStatus::ok) << preset.message;
  const RawParams used = used_params(preset);
  for (const auto& [key, value] : paper) {
    ASSERT_TRUE(used.contains(key)) << key << " in " << preset.technique_params;
    EXPECT_EQ(used.at(key), value) << key;
  }
  const RunResult given = test::harness().run(test::one_frame("illustration_buffer", paper, "torus", {}, 32));
  ASSERT_EQ(given.status, RunStatus::ok) << given.message;
  EXPECT_EQ(largest_difference(preset.image, given.image), 0.0);
  // The defaults (preset=none) are another configuration, with another image.
  const RunResult defaults = test::harness().run(test::one_frame("illustration_buffer", {}, "torus", {}, 32));
  EXPECT_GT(largest_difference(preset.image, defaults.image), 0.0);
  // Explicit parameters win over the preset; the rest keep its values.
  const RunResult mixed = test::harness().run(test::one_frame(
      "illustration_buffer", {{"preset", "paper"}, {"iterations", "5"}, {"storage", "linearized"}}, "torus", {}, 32));
  ASSERT_EQ(mixed.status, RunStatus::ok) << mixed.message;
  const RawParams mixed_used = used_params(mixed);
  EXPECT_EQ(mixed_used.at("iterations"), "5");
  EXPECT_EQ(mixed_used.at("storage"), "linearized");
  EXPECT_EQ(mixed_used.at("neighbors"), "heuristic");
  EXPECT_EQ(mixed_used.at("skip_converged"), "false");
}

}  // namespace
}  // namespace oit
