// Depth peeling: exact against the reference (quads and lit spheres, in any
// submission order) with every fragment peeled and counted; the occlusion
// query early exit costs depth complexity + 1 passes and without it exactly
// max_passes run; a pass cap below the depth complexity leaves an error
// that shrinks strictly as the cap grows, with the un-peeled rest counted;
// fragments tied in depth are all peeled, in submission order; a camera
// whose near plane is at the eye fails loudly; out-of-range parameters are
// rejected naming the parameter.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <utility>
#include <vector>

#include "gl_fixture.h"

namespace oit {
namespace {

constexpr int kSize = 32;
constexpr uint64_t kPixels = uint64_t(kSize) * kSize;
// Layer colour RGBA32F + depth + two RG32UI keys + accumulation RGBA32F, + a 4-byte counter.
constexpr uint64_t kBytes = kPixels * (16 + 4 + 16 + 16) + 4;
const RawParams kQuads32 = {{"layers", "32"}};

RunSpec spec_of(const RawParams& params, const std::string& scene, const RawParams& scene_params, int size,
                const std::string& order = "original") {
  RunSpec spec;
  spec.technique = "depth_peeling";
  spec.params = params;
  spec.scene = scene;
  spec.scene_params = scene_params;
  spec.submission_order = order;
  spec.width = size;
  spec.height = size;
  spec.warmup = 0;
  spec.frames = 1;
  return spec;
}

RunResult run_ok(const RunSpec& spec) {
  RunResult r = test::harness().run(spec);
  EXPECT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_TRUE(r.error.has_value());
  return r;
}

// Writes a glTF file of full-screen unlit quads (z in view space, the colour),
// in this order, seen by an orthographic camera looking down -z. Quads with
// the same z have identical vertices, so their fragments tie exactly in depth.
std::string write_quads_gltf(const std::string& name, const std::vector<std::pair<float, glm::vec4>>& quads,
                             double znear = 0.1) {
  const std::string dir = std::string(OIT_BINARY_DIR) + "/test_output/depth_peeling";
  std::filesystem::create_directories(dir);
  std::vector<float> positions;
  for (const auto& quad : quads) {
    const float corners[4][2] = {{-1.5f, -1.5f}, {1.5f, -1.5f}, {1.5f, 1.5f}, {-1.5f, 1.5f}};
    for (const auto& c : corners) positions.insert(positions.end(), {c[0], c[1], quad.first});
  }
  const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
  std::string bin(positions.size() * 4 + sizeof(indices), '\0');
  std::memcpy(bin.data(), positions.data(), positions.size() * 4);
  std::memcpy(bin.data() + positions.size() * 4, indices, sizeof(indices));
  std::ofstream(dir + "/" + name + ".bin", std::ios::binary) << bin;

  using nlohmann::json;
  json nodes = json::array(), meshes = json::array(), materials = json::array(), accessors = json::array(),
       views = json::array();
  for (size_t i = 0; i < quads.size(); ++i) {
    const glm::vec4& c = quads[i].second;
    const float z = quads[i].first;
    nodes.push_back({{"mesh", i}});
    meshes.push_back({{"primitives", {{{"attributes", {{"POSITION", i}}}, {"indices", quads.size()}, {"material", i}}}}});
    materials.push_back({{"pbrMetallicRoughness", {{"baseColorFactor", {c.r, c.g, c.b, c.a}}}},
                         {"alphaMode", "BLEND"},
                         {"extensions", {{"KHR_materials_unlit", json::object()}}}});
    accessors.push_back({{"bufferView", i}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
                         {"min", {-1.5, -1.5, z}}, {"max", {1.5, 1.5, z}}});
    views.push_back({{"buffer", 0}, {"byteOffset", 48 * i}, {"byteLength", 48}});
  }
  accessors.push_back({{"bufferView", quads.size()}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}});
  views.push_back({{"buffer", 0}, {"byteOffset", 48 * quads.size()}, {"byteLength", 12}});
  nodes.push_back({{"camera", 0}});
  json scene_nodes = json::array();
  for (size_t i = 0; i < nodes.size(); ++i) scene_nodes.push_back(i);
  const json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"KHR_materials_unlit"}},
      {"scene", 0},
      {"scenes", {{{"nodes", scene_nodes}}}},
      {"nodes", nodes},
      {"cameras", {{{"type", "orthographic"}, {"orthographic", {{"xmag", 1.0}, {"ymag", 1.0}, {"znear", znear}, {"zfar", 10.0}}}}}},
      {"meshes", meshes},
      {"materials", materials},
      {"accessors", accessors},
      {"bufferViews", views},
      {"buffers", {{{"uri", name + ".bin"}, {"byteLength", bin.size()}}}},
  };
  const std::string path = dir + "/" + name + ".gltf";
  std::ofstream(path) << gltf.dump(2);
  return path;
}

TEST(DepthPeeling, ExactOnThirtyTwoQuadLayers) {
  for (const std::string order : {"original", "shuffled:7"}) {
    SCOPED_TRACE(order);
    const RunResult r = run_ok(spec_of({}, "quads", kQuads32, kSize, order));
    ASSERT_TRUE(r.error.has_value());
    // Layers are blended in float, the reference in double: only rounding separates them.
    EXPECT_LT(r.error->max_abs, 1e-5);
    EXPECT_EQ(r.counters.fragments_stored, 32u * kPixels);
    EXPECT_EQ(r.counters.fragments_dropped, 0u);
    EXPECT_EQ(r.counters.passes, 33u);  // 32 layers + the pass that finds nothing
    EXPECT_EQ(r.counters.bytes_allocated, kBytes);
  }
}

TEST(DepthPeeling, ExactOnLitSpheresInAnySubmissionOrder) {
  for (const std::string order : {"original", "shuffled:7"}) {
    SCOPED_TRACE(order);
    const RunResult r = run_ok(spec_of({}, "spheres", {}, 48, order));
    ASSERT_TRUE(r.error.has_value());
    ASSERT_GE(r.max_depth_complexity, 4u) << "the spheres must overlap for this test to mean anything";
    EXPECT_LT(r.error->max_abs, 1e-5);
    EXPECT_EQ(r.counters.fragments_stored, r.scene_fragments);
    EXPECT_EQ(r.counters.fragments_dropped, 0u);
    EXPECT_EQ(r.counters.passes, r.max_depth_complexity + 1u);
  }
}

TEST(DepthPeeling, EarlyExitCostsDepthComplexityPlusOnePasses) {
  const RunResult early = run_ok(spec_of({{"early_exit", "true"}}, "quads", {{"layers", "8"}}, kSize));
  EXPECT_EQ(early.max_depth_complexity, 8u);
  EXPECT_EQ(early.counters.passes, 9u);
  EXPECT_LT(early.error->max_abs, 1e-5);
  // Without the query every allowed pass runs; the extra ones peel nothing.
  const RunResult all = run_ok(spec_of({{"early_exit", "false"}, {"max_passes", "13"}}, "quads",
                                       {{"layers", "8"}}, kSize));
  EXPECT_EQ(all.counters.passes, 13u);
  EXPECT_LT(all.error->max_abs, 1e-5);
  EXPECT_EQ(all.counters.fragments_stored, 8u * kPixels);
  EXPECT_EQ(all.counters.fragments_dropped, 0u);
  EXPECT_EQ(all.image.rgba, early.image.rgba);
}

TEST(DepthPeeling, PassCapLeavesAnErrorThatShrinksWithMorePasses) {
  double previous_error = 2.0;
  for (int cap : {4, 8, 16}) {
    SCOPED_TRACE("max_passes=" + std::to_string(cap));
    const RunResult r = run_ok(spec_of({{"max_passes", std::to_string(cap)}}, "quads", kQuads32, kSize));
    ASSERT_TRUE(r.error.has_value());
    EXPECT_GT(r.error->max_abs, 1e-4);
    EXPECT_LT(r.error->max_abs, previous_error);
    previous_error = r.error->max_abs;
    EXPECT_EQ(r.counters.passes, uint64_t(cap));
    // The nearest `cap` layers are peeled; the rest is counted as dropped.
    EXPECT_EQ(r.counters.fragments_stored, uint64_t(cap) * kPixels);
    EXPECT_EQ(r.counters.fragments_dropped, uint64_t(32 - cap) * kPixels);
  }
  // The same cap without early exit gives the same image.
  const RunResult capped = run_ok(spec_of({{"max_passes", "8"}}, "quads", kQuads32, kSize));
  const RunResult no_exit = run_ok(spec_of({{"max_passes", "8"}, {"early_exit", "false"}}, "quads", kQuads32, kSize));
  EXPECT_EQ(capped.image.rgba, no_exit.image.rgba);
  EXPECT_EQ(no_exit.counters.fragments_dropped, 24u * kPixels);
}

TEST(DepthPeeling, DepthTiesArePeeledCompletelyOnePerPass) {
  // One quad in front, then three coplanar quads of different colours whose
  // fragments tie exactly in depth (triangle ids ascend in this order).
  const std::string path = write_quads_gltf(
      "ties", {{-1.0f, {0.9f, 0.9f, 0.1f, 0.3f}}, {-2.0f, {0.9f, 0.1f, 0.1f, 0.5f}},
               {-2.0f, {0.1f, 0.9f, 0.1f, 0.5f}}, {-2.0f, {0.1f, 0.1f, 0.9f, 0.5f}}});
  constexpr int size = 16;
  constexpr uint64_t pixels = uint64_t(size) * size;
  for (const std::string order : {"original", "reversed", "shuffled:3"}) {
    SCOPED_TRACE(order);
    const RunResult r = run_ok(spec_of({}, path, {}, size, order));
    EXPECT_EQ(r.max_depth_complexity, 4u);
    // Every tied fragment is peeled in a pass of its own, in submission order; none is lost.
    EXPECT_EQ(r.counters.fragments_stored, 4u * pixels);
    EXPECT_EQ(r.counters.fragments_dropped, 0u);
    EXPECT_EQ(r.counters.passes, 5u);
    if (order == "original") {
      // Submitted in id order, the tie is peeled in the reference's order.
      EXPECT_LT(r.error->max_abs, 1e-5);
    }
  }
  // Reversed, the tie is peeled in reverse id order: the image differs from
  // the reference, which breaks ties by id.
  const RunResult reversed = run_ok(spec_of({}, path, {}, size, "reversed"));
  EXPECT_GT(reversed.error->max_abs, 0.05);
}

TEST(DepthPeeling, RefusesACameraWhoseNearPlaneIsAtTheEye) {
  // Depths <= 0 cannot be ordered by the depth test; rather than merging
  // layers silently the run fails, naming the technique and the range.
  const std::string path = write_quads_gltf("near_zero", {{-1.0f, {0.9f, 0.1f, 0.1f, 0.5f}}}, 0.0);
  const RunResult r = test::harness().run(spec_of({}, path, {}, 8));
  EXPECT_EQ(r.status, RunStatus::error);
  EXPECT_NE(r.message.find("depth_peeling"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("near plane"), std::string::npos) << r.message;
}

TEST(DepthPeeling, RejectsOutOfRangeParametersNamingThem) {
  for (const std::string bad : {"0", "4097", "many"}) {
    const RunResult r = test::harness().run(spec_of({{"max_passes", bad}}, "quads", {{"layers", "2"}}, 8));
    EXPECT_EQ(r.status, RunStatus::error);
    EXPECT_NE(r.message.find("max_passes"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("depth_peeling"), std::string::npos) << r.message;
  }
  const RunResult r = test::harness().run(spec_of({{"early_exit", "maybe"}}, "quads", {{"layers", "2"}}, 8));
  EXPECT_EQ(r.status, RunStatus::error);
  EXPECT_NE(r.message.find("early_exit"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace oit
