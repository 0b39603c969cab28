#include "scenes/mesh_loader.h"

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "scenes/mesh_file_check.h"
#include "scenes/regular_file.h"

namespace oit {
namespace {

// Beyond these the scene would not fit a GPU buffer sensibly (Vertex is 64
// bytes); refusing early keeps a corrupt file from allocating gigabytes.
constexpr uint64_t kMaxVertices = uint64_t(1) << 25;
constexpr uint64_t kMaxTriangles = uint64_t(1) << 26;

using OpenMesh::EdgeHandle;
using OpenMesh::FaceHandle;
using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;

// Takes what an OpenMesh reader parses as raw indexed polygons. Unlike
// OpenMesh's own ImporterT it builds no half-edge structure, so no face is
// refused for being non-manifold and no vertex is duplicated: the indices
// stay those of the file. Problems are recorded (not thrown through the
// reader) and reported after it returns.
class PolygonCollector final : public OpenMesh::IO::BaseImporter {
 public:
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<uint8_t> has_normal;
  std::vector<uint32_t> corners;
  std::vector<size_t> polygon_starts{0};
  std::string problem;

  VertexHandle add_vertex(const OpenMesh::Vec3f& p) override {
    if (positions.size() >= kMaxVertices) {
      note("more than " + std::to_string(kMaxVertices) + " vertices");
      return VertexHandle();
    }
    positions.emplace_back(p[0], p[1], p[2]);
    normals.emplace_back(0.0f);
    has_normal.push_back(0);
    return VertexHandle(int(positions.size() - 1));
  }
  VertexHandle add_vertex() override { return add_vertex(OpenMesh::Vec3f(0.0f, 0.0f, 0.0f)); }
  FaceHandle add_face(const VHandles& handles) override {
    if (handles.size() < 3) {
      note("a face has " + std::to_string(handles.size()) + " corners");
      return FaceHandle();
    }
    for (const VertexHandle& h : handles) {
      if (!valid(h)) {
        note("a face references vertex " + std::to_string(h.idx()) + ", but there are only " +
             std::to_string(positions.size()) + " vertices");
        return FaceHandle();
      }
    }
    if (corners.size() + handles.size() > 3 * kMaxTriangles) {
      note("more than " + std::to_string(kMaxTriangles) + " triangles");
      return FaceHandle();
    }
    for (const VertexHandle& h : handles) corners.push_back(uint32_t(h.idx()));
    polygon_starts.push_back(corners.size());
    return FaceHandle(int(polygon_starts.size() - 2));
  }
  void set_point(VertexHandle h, const OpenMesh::Vec3f& p) override {
    if (valid(h)) positions[size_t(h.idx())] = glm::vec3(p[0], p[1], p[2]);
  }
  void set_normal(VertexHandle h, const OpenMesh::Vec3f& n) override {
    if (!valid(h)) return;
    normals[size_t(h.idx())] = glm::vec3(n[0], n[1], n[2]);
    has_normal[size_t(h.idx())] = 1;
  }
  void set_normal(VertexHandle h, const OpenMesh::Vec3d& n) override {
    set_normal(h, OpenMesh::Vec3f(float(n[0]), float(n[1]), float(n[2])));
  }
  size_t n_vertices() const override { return positions.size(); }
  size_t n_faces() const override { return polygon_starts.size() - 1; }
  size_t n_edges() const override { return 0; }

  // Everything else a reader may hand over is not part of a Scene.
  HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return HalfedgeHandle(); }
  FaceHandle add_face(HalfedgeHandle) override { return FaceHandle(); }
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec2f>&) override {}
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec3f>&) override {}
  void set_face_texindex(FaceHandle, int) override {}
  void set_halfedge(VertexHandle, HalfedgeHandle) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec2f&) override {}
  void set_status(VertexHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_next(HalfedgeHandle, HalfedgeHandle) override {}
  void set_face(HalfedgeHandle, FaceHandle) override {}
  void request_face_texcoords2D() override {}
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec2f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec3f&) override {}
  void set_status(HalfedgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec3f&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec4f&) override {}
  void set_status(EdgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3d&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4f&) override {}
  void set_status(FaceHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void add_texture_information(int, std::string) override {}

 private:
  bool valid(VertexHandle h) const { return h.is_valid() && size_t(h.idx()) < positions.size(); }
  void note(const std::string& what) {
    if (problem.empty()) problem = what;
  }
};

// OpenMesh reports through its own streams (missing material files,
// skipped faces); the loader reports through exceptions instead.
class QuietOpenMesh {
 public:
  QuietOpenMesh() : err_(omerr().is_enabled()), log_(omlog().is_enabled()), out_(omout().is_enabled()) {
    omerr().disable();
    omlog().disable();
    omout().disable();
  }
  ~QuietOpenMesh() {
    if (err_) omerr().enable();
    if (log_) omlog().enable();
    if (out_) omout().enable();
  }

 private:
  bool err_, log_, out_;
};

std::string lower_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension.empty() ? extension : extension.substr(1);
}

// Union-find over vertices: a face joins all its corners.
class Components {
 public:
  explicit Components(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), uint32_t(0)); }
  uint32_t root(uint32_t v) {
    while (parent_[v] != v) v = parent_[v] = parent_[parent_[v]];
    return v;
  }
  void join(uint32_t a, uint32_t b) {
    a = root(a);
    b = root(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<uint32_t> parent_;
};

}  // namespace

glm::vec4 mesh_component_color(uint32_t component) {
  static constexpr std::array<glm::vec3, 8> palette = {
      glm::vec3(0.90f, 0.35f, 0.25f), glm::vec3(0.25f, 0.60f, 0.90f), glm::vec3(0.35f, 0.80f, 0.35f),
      glm::vec3(0.95f, 0.75f, 0.20f), glm::vec3(0.65f, 0.40f, 0.85f), glm::vec3(0.20f, 0.80f, 0.75f),
      glm::vec3(0.90f, 0.50f, 0.70f), glm::vec3(0.60f, 0.60f, 0.60f)};
  return glm::vec4(palette[component % palette.size()], kMeshAlpha);
}

bool is_mesh_file(const std::string& path) {
  const std::string extension = lower_extension(path);
  return extension == "obj" || extension == "off" || extension == "ply" || extension == "stl";
}

namespace {

// OpenMesh's read of `path` into `collector`, its messages silenced. OpenMesh
// picks its reader by the lower-case extension: a file named otherwise is
// read through a temporary link so named.
bool read_with_openmesh(const std::string& path, const std::string& format, PolygonCollector& collector) {
  QuietOpenMesh quiet;
  OpenMesh::IO::Options options = OpenMesh::IO::Options::VertexNormal;
  std::string readable = path;
  const std::string extension = std::filesystem::path(path).extension().string();
  std::filesystem::path alias;
  if (extension != "." + format) {
    alias = std::filesystem::temp_directory_path() /
            ("oitbench_mesh_" + std::to_string(std::hash<std::string>{}(path)) + "." + format);
    std::error_code error;
    std::filesystem::remove(alias, error);
    std::filesystem::create_symlink(std::filesystem::absolute(path), alias, error);
    if (error) throw std::invalid_argument(path + ": cannot give it a lower-case extension: " + error.message());
    readable = alias.string();
  }
  const bool read_ok = OpenMesh::IO::IOManager().read(readable, collector, options);
  if (!alias.empty()) {
    std::error_code error;
    std::filesystem::remove(alias, error);
  }
  return read_ok;
}

// Throws unless OpenMesh read what check_mesh_file() counted in the file;
// returns the polygons read.
size_t checked_polygons(const std::string& path, const std::string& format, const MeshFileFacts& facts,
                        const PolygonCollector& collector, bool read_ok) {
  if (!collector.problem.empty()) throw std::invalid_argument(path + ": " + collector.problem);
  if (!read_ok) throw std::invalid_argument(path + ": OpenMesh could not read it as " + format);
  const size_t polygons = collector.polygon_starts.size() - 1;
  if (format != "stl" && collector.positions.size() != facts.vertices) {
    throw std::invalid_argument(path + ": OpenMesh read " + std::to_string(collector.positions.size()) +
                                " vertices where the file has " + std::to_string(facts.vertices));
  }
  if ((format == "off" || format == "ply") && polygons != facts.faces) {
    throw std::invalid_argument(path + ": OpenMesh read " + std::to_string(polygons) + " faces where the file has " +
                                std::to_string(facts.faces));
  }
  if (polygons == 0) throw std::invalid_argument(path + ": contains no faces");
  return polygons;
}

constexpr uint32_t kUnused = UINT32_MAX;

// The vertices the faces use, one object per connected component; returns
// each file vertex's index in the scene (kUnused for those dropped).
std::vector<uint32_t> add_used_vertices(const PolygonCollector& collector, size_t polygons, Scene& scene) {
  const size_t file_vertices = collector.positions.size();
  Components components(file_vertices);
  std::vector<uint8_t> used(file_vertices, 0);
  for (size_t p = 0; p < polygons; ++p) {
    const size_t begin = collector.polygon_starts[p], end = collector.polygon_starts[p + 1];
    for (size_t c = begin; c < end; ++c) {
      used[collector.corners[c]] = 1;
      if (c > begin) components.join(collector.corners[begin], collector.corners[c]);
    }
  }
  std::vector<uint32_t> new_index(file_vertices, kUnused), component_of_root(file_vertices, kUnused);
  for (size_t v = 0; v < file_vertices; ++v) {
    if (!used[v]) continue;
    new_index[v] = uint32_t(scene.vertices.size());
    uint32_t& component = component_of_root[components.root(uint32_t(v))];
    if (component == kUnused) component = scene.object_count++;
    Vertex vertex;
    vertex.position = collector.positions[v];
    vertex.normal = glm::vec3(0.0f);
    vertex.color = mesh_component_color(component);
    vertex.object_id = component;
    vertex.surface_id = component;
    scene.vertices.push_back(vertex);
  }
  return new_index;
}

// Each polygon as a fan of triangles, accumulating area-weighted face
// normals into its vertices (a zero-area triangle adds nothing).
void add_polygon_fans(const PolygonCollector& collector, size_t polygons, const std::vector<uint32_t>& new_index,
                      Scene& scene) {
  for (size_t p = 0; p < polygons; ++p) {
    const size_t begin = collector.polygon_starts[p], end = collector.polygon_starts[p + 1];
    for (size_t c = begin + 1; c + 1 < end; ++c) {
      const uint32_t a = new_index[collector.corners[begin]], b = new_index[collector.corners[c]],
                     d = new_index[collector.corners[c + 1]];
      scene.indices.insert(scene.indices.end(), {a, b, d});
      scene.triangle_ids.push_back(uint32_t(scene.triangle_ids.size()));
      const glm::vec3 n = glm::cross(scene.vertices[b].position - scene.vertices[a].position,
                                     scene.vertices[d].position - scene.vertices[a].position);
      for (uint32_t k : {a, b, d}) scene.vertices[k].normal += n;
    }
  }
}

// The file's normal where it has a usable one, else the accumulated face
// normals, normalised (+z where both are zero).
void finish_normals(const PolygonCollector& collector, const std::vector<uint32_t>& new_index, Scene& scene) {
  for (size_t v = 0; v < new_index.size(); ++v) {
    if (new_index[v] == kUnused) continue;
    glm::vec3& normal = scene.vertices[new_index[v]].normal;
    const glm::vec3 file_normal = collector.normals[v];
    const float file_length = glm::length(file_normal);
    if (collector.has_normal[v] && std::isfinite(file_length) && file_length > 0.0f) {
      normal = file_normal / file_length;
    } else {
      const float length = glm::length(normal);
      normal = std::isfinite(length) && length > 0.0f ? normal / length : glm::vec3(0.0f, 0.0f, 1.0f);
    }
  }
}

}  // namespace

Scene load_mesh_scene(const std::string& path) {
  const std::string format = lower_extension(path);
  const std::string bytes = read_regular_file(path, kMaxSceneFileBytes);
  const MeshFileFacts facts = check_mesh_file(path, format, bytes);
  PolygonCollector collector;
  const bool read_ok = read_with_openmesh(path, format, collector);
  const size_t polygons = checked_polygons(path, format, facts, collector, read_ok);
  Scene scene;
  scene.name = path;
  const std::vector<uint32_t> new_index = add_used_vertices(collector, polygons, scene);
  add_polygon_fans(collector, polygons, new_index, scene);
  finish_normals(collector, new_index, scene);
  scene.lit = true;
  scene.camera = frame_bounding_sphere(scene.bounds());
  scene.validate();
  return scene;
}

}  // namespace oit
