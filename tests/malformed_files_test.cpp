// Every loader (OBJ, OFF, PLY, STL through OpenMesh; glTF/GLB through
// tinygltf) on a corpus of malformed files written here: each must end in a
// std::invalid_argument naming the file (and, for the hand-made cases, the
// problem), never a crash, a hang, another exception or a giant allocation.
// Then every truncation and a few thousand seeded byte mutations of small
// valid files: each either loads or is rejected cleanly.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>

#include "scenes/scene_library.h"
#include "tests/gl_fixture.h"

namespace oit {
namespace {

const std::string kDir = std::string(OIT_BINARY_DIR) + "/test_output/malformed";

// Loads `path`; true when it loaded. A rejection must be an invalid_argument
// whose message names the file (and contains `problem` when given).
bool loads_or_rejects_cleanly(const std::string& path, const std::string& problem = "") {
  const std::string file = std::filesystem::path(path).filename().string();
  try {
    const Scene scene = load_scene(path, {});
    EXPECT_GT(scene.triangle_count(), 0u) << path;
    return true;
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(file), std::string::npos) << "the message does not name the file: " << message;
    if (!problem.empty()) {
      EXPECT_NE(message.find(problem), std::string::npos) << message;
    }
  } catch (const std::exception& e) {
    ADD_FAILURE() << path << ": " << typeid(e).name() << " instead of std::invalid_argument: " << e.what();
  }
  return false;
}

void expect_rejected(const std::string& name, const std::string& bytes, const std::string& problem) {
  EXPECT_FALSE(loads_or_rejects_cleanly(test::write_test_file("malformed", name, bytes), problem)) << name << " loaded";
}

std::string floats(std::initializer_list<float> values) {
  std::string bytes;
  for (float v : values) bytes.append(reinterpret_cast<const char*>(&v), 4);
  return bytes;
}

template <typename T>
std::string raw(T value) {
  return std::string(reinterpret_cast<const char*>(&value), sizeof value);
}

const std::string kObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n";
const std::string kOff = "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n";
const std::string kPlyHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
const std::string kPly = kPlyHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
const std::string kStlAscii =
    "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";

std::string binary_ply(const std::string& index_list_type, const std::string& body) {
  return "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
         "property float z\nelement face 1\nproperty list " +
         index_list_type + " vertex_indices\nend_header\n" + body;
}
const std::string kPlyBinaryVertices = floats({0, 0, 0, 1, 0, 0, 0, 1, 0});

std::string binary_stl(uint32_t declared, const std::string& facets) { return std::string(80, 'x') + raw(declared) + facets; }
std::string stl_facet(std::initializer_list<float> corners) { return floats({0, 0, 1}) + floats(corners) + std::string(2, '\0'); }

TEST(MalformedFiles, MeshFilesAreRejectedNamingFileAndProblem) {
  for (const char* extension : {"obj", "off", "ply", "stl"}) expect_rejected(std::string("empty.") + extension, "", "empty");
  // OBJ
  expect_rejected("past.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 5\n", "vertex 5");
  expect_rejected("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "not finite");
  expect_rejected("inf.obj", "v 0 0 0\nv 1 -inf 0\nv 0 1 0\nf 1 2 3\n", "not finite");
  expect_rejected("huge.obj", "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n", "out of range");
  expect_rejected("zero_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "index 0");
  expect_rejected("relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 -2 -1\n", "before the first vertex");
  expect_rejected("two_corners.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", "2 corners");
  expect_rejected("no_position.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf //1 2 3\n", "no valid vertex index");
  expect_rejected("short_vertex.obj", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "missing");
  expect_rejected("hex.obj", "v 0 0 0\nv 0x1p3 0 0\nv 0 1 0\nf 1 2 3\n", "not a number");
  expect_rejected("no_faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "no faces");
  std::filesystem::create_directories(kDir + "/a_directory.mtl");
  expect_rejected("mtllib_dir.obj", "mtllib a_directory.mtl\n" + kObj, "not a regular file");
  // OFF
  expect_rejected("truncated.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n", "declares 3 vertices");
  expect_rejected("truncated_face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1", "declares 1 faces");
  expect_rejected("huge_counts.off", "OFF\n2000000000 2000000000 0\n0 0 0\n", "declares 2000000000 vertices");
  expect_rejected("huge_faces.off", "OFF\n3 2000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "declares 2000000000 faces");
  expect_rejected("past.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n", "vertex 5");
  expect_rejected("huge_face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n", "corner count");
  expect_rejected("big_face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n60000 0 1 2\n", "corners in face 0");
  expect_rejected("negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "not a number");
  expect_rejected("nan.off", "OFF\n3 1 0\n0 0 0\n1 NaN 0\n0 1 0\n3 0 1 2\n", "not finite");
  expect_rejected("no_faces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", "no faces");
  expect_rejected("not_off.off", "hello\n3 1 0\n", "OFF header");
  expect_rejected("binary.off", "OFF BINARY\n" + raw(uint32_t(3)), "binary OFF");
  expect_rejected("counts_on_header.off", "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "next line");
  // PLY
  expect_rejected("truncated.ply", kPlyHeader + "0 0 0\n1 0 0\n", "declares 3 vertex");
  expect_rejected("past.ply", kPlyHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n", "vertex 9");
  expect_rejected("no_end.ply", "ply\nformat ascii 1.0\nelement vertex 3\n", "end_header");
  expect_rejected("no_x.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float y\nend_header\n0\n", "'x'");
  expect_rejected("vertex_list.ply",
                  "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                  "property list uchar float extra\nend_header\n0 0 0 1 5\n",
                  "list property 'extra'");
  std::string huge_ply = binary_ply("uchar int", "");
  huge_ply.replace(huge_ply.find("vertex 3"), 8, "vertex 4000000000");
  expect_rejected("huge.ply", huge_ply, "declares 4000000000");
  expect_rejected("huge_list.ply",
                  binary_ply("uint int", kPlyBinaryVertices + raw(uint32_t(4000000000u)) + raw(int32_t(0))),
                  "out of range");
  expect_rejected("nan.ply",
                  binary_ply("uchar int", floats({0, 0, 0, std::nanf(""), 0, 0, 0, 1, 0}) + "\x03" +
                                              raw(int32_t(0)) + raw(int32_t(1)) + raw(int32_t(2))),
                  "not finite");
  expect_rejected("negative_index.ply",
                  binary_ply("uchar int", kPlyBinaryVertices + "\x03" + raw(int32_t(0)) + raw(int32_t(-1)) +
                                              raw(int32_t(2))),
                  "vertex -1");
  expect_rejected("truncated_binary.ply", binary_ply("uchar int", kPlyBinaryVertices + "\x03" + raw(int32_t(0))),
                  "face 0");
  expect_rejected("bad_format.ply", "ply\nformat xml 1.0\nend_header\n", "unknown format");
  // OpenMesh reads the header word by word: a property without a name took
  // "end_header" as its name and OpenMesh's header parser then looped
  // forever (a fuzzer finding); a word too many would be its next keyword.
  const std::string vertex_xyz = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n";
  expect_rejected("unnamed_property.ply", vertex_xyz + "property float\nend_header\n0 0 0\n1 0 0\n0 1 0\n",
                  "header line 6: the property name is missing");
  expect_rejected("unnamed_element.ply", "ply\nformat ascii 1.0\nelement\nend_header\n",
                  "header line 3: the element name is missing");
  expect_rejected("extra_word.ply", vertex_xyz + "property float z w\nend_header\n", "unexpected 'w'");
  expect_rejected("extra_after_end.ply", vertex_xyz + "property float z\nend_header 0\n0 0 0\n", "unexpected '0'");
  // It takes the three words after "ply" as the format line: a version that
  // is no number stopped its stream and its header parser looped forever.
  expect_rejected("format_not_second.ply", "ply\nfot ascii ply\nformat ascii 1.0\nend_header\n",
                  "header line 2: the format line must be line 2");
  // Free text is read word by word too (Blender's "Created by" line is fine).
  expect_rejected("keyword_in_text.ply", vertex_xyz + "property float z\nelerty list property float x\nend_header\n",
                  "the keyword 'property' inside a 'elerty' line");
  expect_rejected("obj_info_keyword.ply", vertex_xyz + "property float z\nobj_info element\nend_header\n",
                  "the keyword 'element' inside a 'obj_info' line");
  // STL
  expect_rejected("truncated.stl", binary_stl(1000, stl_facet({0, 0, 0, 1, 0, 0, 0, 1, 0})), "1000 facets");
  expect_rejected("huge.stl", binary_stl(4000000000u, stl_facet({0, 0, 0, 1, 0, 0, 0, 1, 0})), "4000000000 facets");
  expect_rejected("nan.stl", binary_stl(1, stl_facet({0, 0, 0, 1, std::nanf(""), 0, 0, 1, 0})), "not finite");
  expect_rejected("inf.stl",
                  binary_stl(1, stl_facet({0, 0, 0, 1, 0, 0, 0, std::numeric_limits<float>::infinity(), 0})),
                  "not finite");
  expect_rejected("nan_ascii.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex nan 0 0\n"
                  "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n", "not finite");
  expect_rejected("cut_ascii.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", "truncated");
  expect_rejected("no_facets.stl", "solid t\nendsolid t\n", "no faces");
  expect_rejected("degenerate_only.stl", binary_stl(1, stl_facet({0, 0, 0, 0, 0, 0, 0, 1, 0})), "no faces");
}

// A .glb of `json` with `bin` as its buffer.
std::string glb(const nlohmann::json& json, const std::string& bin) {
  std::string text = json.dump();
  while (text.size() % 4) text += ' ';
  std::string padded = bin;
  while (padded.size() % 4) padded += '\0';
  std::string out = "glTF" + raw(uint32_t(2)) + raw(uint32_t(12 + 8 + text.size() + 8 + padded.size()));
  out += raw(uint32_t(text.size())) + raw(uint32_t(0x4E4F534A)) + text;
  out += raw(uint32_t(padded.size())) + raw(uint32_t(0x004E4942)) + padded;
  return out;
}

// One triangle, in a .glb whose JSON the cases below break one way each.
nlohmann::json triangle_json(size_t bin_size) {
  using nlohmann::json;
  return {{"asset", {{"version", "2.0"}}},
          {"scenes", {{{"nodes", {0}}}}},
          {"nodes", {{{"mesh", 0}}}},
          {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
          {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}},
                         {{"bufferView", 1}, {"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}}}},
          {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
                           {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 6}}}},
          {"buffers", {{{"byteLength", bin_size}}}}};
}

std::string triangle_bin(float corner_x = 1.0f) {
  return floats({0, 0, 0, corner_x, 0, 0, 0, 1, 0}) + raw(uint16_t(0)) + raw(uint16_t(1)) + raw(uint16_t(2));
}

TEST(MalformedFiles, GltfFilesAreRejectedNamingFileAndProblem) {
  const std::string bin = triangle_bin();
  const nlohmann::json good = triangle_json(bin.size());
  ASSERT_TRUE(loads_or_rejects_cleanly(test::write_test_file("malformed", "good.glb", glb(good, bin))));
  expect_rejected("empty.glb", "", "cannot load glTF");
  expect_rejected("empty.gltf", "", "cannot load glTF");
  const std::string whole = glb(good, bin);
  expect_rejected("truncated.glb", whole.substr(0, whole.size() / 2), "cannot load glTF");
  expect_rejected("header_only.glb", whole.substr(0, 20), "cannot load glTF");
  std::string long_chunk = whole;
  std::memcpy(long_chunk.data() + 12, "\xf0\xff\xff\xff", 4);  // JSON chunk length past the end
  expect_rejected("long_chunk.glb", long_chunk, "cannot load glTF");

  auto broken = [&](const std::string& name, const std::function<void(nlohmann::json&)>& edit,
                    const std::string& problem, const std::string& data = "") {
    nlohmann::json json = good;
    edit(json);
    expect_rejected(name, glb(json, data.empty() ? bin : data), problem);
  };
  broken("count_past_buffer.glb", [](auto& j) { j["accessors"][0]["count"] = 1000000000000ull; }, "reads past the end");
  broken("unbacked_count.glb", [](auto& j) {
    j["accessors"][0].erase("bufferView");
    j["accessors"][0]["count"] = 1000000000000ull;
  }, "without a buffer view");
  broken("huge_stride.glb", [](auto& j) { j["bufferViews"][0]["byteStride"] = 252; }, "past the end");
  broken("view_past_buffer.glb", [](auto& j) { j["bufferViews"][1]["byteLength"] = 4000; }, "past the end");
  broken("index_past.glb", [](auto&) {}, "past its 3 vertices", floats({0, 0, 0, 1, 0, 0, 0, 1, 0}) +
                                                                       raw(uint16_t(0)) + raw(uint16_t(1)) +
                                                                       raw(uint16_t(7)));
  broken("float_indices.glb", [](auto& j) { j["accessors"][1]["componentType"] = 5126; }, "unsigned");
  broken("nan_position.glb", [](auto&) {}, "non-finite", triangle_bin(std::nanf("")));
  broken("cycle.glb", [](auto& j) {
    j["nodes"] = {{{"mesh", 0}, {"children", {1}}}, {{"children", {0}}}};
  }, "reached twice");
  broken("shared_child.glb", [](auto& j) {
    j["scenes"][0]["nodes"] = {0, 1};
    j["nodes"] = {{{"children", {2}}}, {{"children", {2}}}, {{"mesh", 0}}};
  }, "reached twice");
  broken("points.glb", [](auto& j) { j["meshes"][0]["primitives"][0]["mode"] = 0; }, "only triangles");
  broken("bad_mesh.glb", [](auto& j) { j["nodes"][0]["mesh"] = 5; }, "mesh index out of range");
  broken("no_triangles.glb", [](auto& j) { j["nodes"][0].erase("mesh"); }, "no triangles");
  broken("bad_camera.glb", [](auto& j) {
    j["nodes"][0]["camera"] = 0;
    j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.0}, {"znear", 0.1}}}}};
  }, "");
  expect_rejected("missing_bin.gltf", R"({"asset":{"version":"2.0"},"buffers":[{"uri":"nowhere.bin","byteLength":8}]})",
                  "cannot load glTF");
}

TEST(MalformedFiles, AssimpsBrokenGltfSamplesAreRejectedCleanly) {
  // assimp-testmodels ships deliberately broken glTF files.
  const std::string root = "/usr/share/assimp/models/glTF2/";
  ASSERT_TRUE(std::filesystem::exists(root)) << root << " missing: setup.sh installs assimp-testmodels";
  for (const std::string dir : {"IndexOutOfRange", "BoxWithInfinites-glTF-Binary", "RecursiveNodes", "MissingBin",
                                "IncorrectVertexArrays", "wrongTypes", "SchemaFailures", "TestNoRootNode"}) {
    if (!std::filesystem::exists(root + dir)) continue;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root + dir)) {
      const std::string extension = entry.path().extension().string();
      if (extension == ".gltf" || extension == ".glb") loads_or_rejects_cleanly(entry.path().string());
    }
  }
  EXPECT_FALSE(loads_or_rejects_cleanly(root + "BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "non-finite"));
}

// Small valid files of every format, the seeds of the sweep below.
std::vector<std::pair<std::string, std::string>> valid_samples() {
  const std::string bin = triangle_bin();
  return {{"obj", kObj},
          {"off", kOff},
          {"ply", kPly},
          {"ply", binary_ply("uchar int", kPlyBinaryVertices + "\x03" + raw(int32_t(0)) + raw(int32_t(1)) +
                                              raw(int32_t(2)))},
          {"stl", kStlAscii},
          {"stl", binary_stl(2, stl_facet({0, 0, 0, 1, 0, 0, 0, 1, 0}) + stl_facet({1, 0, 0, 1, 1, 0, 0, 1, 0}))},
          {"glb", glb(triangle_json(bin.size()), bin)}};
}

TEST(MalformedFiles, EveryTruncationLoadsOrIsRejectedCleanly) {
  for (const auto& [format, bytes] : valid_samples()) {
    ASSERT_TRUE(loads_or_rejects_cleanly(test::write_test_file("malformed", "whole." + format, bytes))) << format;
    for (size_t length = 0; length < bytes.size(); ++length)
      loads_or_rejects_cleanly(
          test::write_test_file("malformed", "cut_" + std::to_string(length) + "." + format, bytes.substr(0, length)));
  }
}

TEST(MalformedFiles, SeededMutationsLoadOrAreRejectedCleanly) {
  std::mt19937 rng(20240917);
  const std::string interesting[] = {"9", "99999999999", "-", "-1", "0", "\xff", std::string(1, '\0'), " ", "\n",
                                     "nan", "1e39", "4294967295", ".", "/", "end_header", "solid"};
  size_t loaded = 0, rejected = 0;
  for (const auto& [format, bytes] : valid_samples()) {
    for (int round = 0; round < 400; ++round) {
      std::string mutated = bytes;
      const int edits = 1 + int(rng() % 3);
      for (int e = 0; e < edits && !mutated.empty(); ++e) {
        const size_t at = rng() % mutated.size();
        switch (rng() % 3) {
          case 0: mutated[at] = char(rng() & 0xff); break;
          case 1: mutated.replace(at, 1 + rng() % 3, interesting[rng() % std::size(interesting)]); break;
          default: mutated.insert(at, interesting[rng() % std::size(interesting)]); break;
        }
      }
      const std::string name = "mutant_" + std::to_string(round % 8) + "." + format;
      (loads_or_rejects_cleanly(test::write_test_file("malformed", name, mutated)) ? loaded : rejected) += 1;
    }
  }
  // Both outcomes occur: the mutations are neither all harmless nor all fatal.
  EXPECT_GT(loaded, 100u);
  EXPECT_GT(rejected, 100u);
}

}  // namespace
}  // namespace oit
