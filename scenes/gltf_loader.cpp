#include "scenes/gltf_loader.h"

#include <tiny_gltf.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "scenes/regular_file.h"

namespace oit {
namespace {

// An accessor without a buffer view is all zeros of any declared length;
// beyond this it is a corrupt file, not a mesh.
constexpr size_t kMaxUnbackedElements = size_t(1) << 24;
// Instancing multiplies geometry: refuse scenes that would not fit in memory.
constexpr size_t kMaxVertices = size_t(1) << 25;
constexpr size_t kMaxTriangles = size_t(1) << 26;
// The range of scene sizes that rendering in float handles: the bounding
// sphere, the framing camera's depth range and the projection square and
// invert lengths, which overflow or vanish (NaN pixels, or no fragments at
// all) well before a coordinate itself stops being finite.
constexpr double kLargestCoordinate = 1e16;
constexpr double kSmallestExtent = 1e-16;
// Fewer float steps than this across the scene at its farthest coordinate,
// and its vertices snap together: a model moved far from the origin.
constexpr double kLeastStepsAcross = 128.0;

// The scene needs no textures: images are neither decoded nor required.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

class GltfReader {
 public:
  GltfReader(const tinygltf::Model& model, const std::string& path) : model_(model), path_(path) {}

  [[noreturn]] void fail(const std::string& what) const { throw std::invalid_argument(path_ + ": " + what); }

  // Reads `components` values per element of an accessor as doubles, with
  // every offset checked against the buffer it points into.
  std::vector<double> read(int accessor_index, int components) const {
    if (accessor_index < 0 || size_t(accessor_index) >= model_.accessors.size())
      fail("accessor " + std::to_string(accessor_index) + " does not exist");
    const auto& accessor = model_.accessors[size_t(accessor_index)];
    if (accessor.sparse.isSparse) fail("sparse accessor " + std::to_string(accessor_index) + " is not supported");
    const int have = tinygltf::GetNumComponentsInType(uint32_t(accessor.type));
    if (have != components)
      fail("accessor " + std::to_string(accessor_index) + " has " + std::to_string(have) + " components, expected " +
           std::to_string(components));
    const int component_size = tinygltf::GetComponentSizeInBytes(uint32_t(accessor.componentType));
    if (component_size <= 0) fail("accessor " + std::to_string(accessor_index) + " has an invalid component type");
    const std::string name = "accessor " + std::to_string(accessor_index);
    if (accessor.bufferView < 0) {
      // All zeros by the spec, so no buffer bounds the count: cap it.
      if (accessor.count > kMaxUnbackedElements)
        fail(name + " declares " + std::to_string(accessor.count) + " elements without a buffer view");
      return std::vector<double>(accessor.count * size_t(components), 0.0);
    }
    if (size_t(accessor.bufferView) >= model_.bufferViews.size()) fail(name + ": buffer view out of range");
    const auto& view = model_.bufferViews[size_t(accessor.bufferView)];
    if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size()) fail(name + ": buffer out of range");
    const auto& buffer = model_.buffers[size_t(view.buffer)].data;
    // Every bound below is checked without overflow, BEFORE anything is
    // allocated from the declared count.
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
      fail("buffer view " + std::to_string(accessor.bufferView) + " runs past the end of its buffer");
    if (accessor.byteOffset > view.byteLength) fail(name + " starts past the end of its buffer view");
    const size_t element_size = size_t(component_size) * size_t(components);
    const size_t stride = view.byteStride ? view.byteStride : element_size;
    const size_t start = view.byteOffset + accessor.byteOffset;
    const size_t available = view.byteLength - accessor.byteOffset;
    if (accessor.count > 0 && (element_size > available || (accessor.count - 1) > (available - element_size) / stride))
      fail(name + " (" + std::to_string(accessor.count) + " elements) reads past the end of its buffer view");
    std::vector<double> values(accessor.count * size_t(components), 0.0);
    for (size_t i = 0; i < accessor.count; ++i) {
      const unsigned char* element = buffer.data() + start + i * stride;
      for (int c = 0; c < components; ++c) {
        values[i * size_t(components) + size_t(c)] =
            component(element + size_t(c) * size_t(component_size), accessor.componentType, accessor.normalized);
      }
    }
    return values;
  }

 private:
  static double component(const unsigned char* p, int type, bool normalized) {
    switch (type) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: { float v; std::memcpy(&v, p, 4); return v; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t v; std::memcpy(&v, p, 4); return v; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t v; std::memcpy(&v, p, 2); return normalized ? v / 65535.0 : v; }
      case TINYGLTF_COMPONENT_TYPE_SHORT: { int16_t v; std::memcpy(&v, p, 2); return normalized ? std::max(v / 32767.0, -1.0) : v; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? *p / 255.0 : *p;
      case TINYGLTF_COMPONENT_TYPE_BYTE: { auto v = static_cast<int8_t>(*p); return normalized ? std::max(v / 127.0, -1.0) : v; }
      default: return 0.0;
    }
  }

  const tinygltf::Model& model_;
  const std::string& path_;
};

glm::mat4 local_transform(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data());
  glm::mat4 m(1.0f);
  if (node.translation.size() == 3) m = glm::translate(m, glm::vec3(glm::make_vec3(node.translation.data())));
  if (node.rotation.size() == 4) {
    const glm::quat q(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]), float(node.rotation[2]));
    m *= glm::mat4_cast(q);
  }
  if (node.scale.size() == 3) m = glm::scale(m, glm::vec3(glm::make_vec3(node.scale.data())));
  return m;
}

// The camera of a node whose world transform is `world`: orthographic or
// perspective, checked for a usable size and depth range.
Camera read_camera(const tinygltf::Camera& source, const glm::mat4& world, const GltfReader& reader) {
  Camera c;
  c.view = glm::inverse(world);
  if (source.type == "orthographic") {
    c.orthographic = true;
    c.xmag = std::abs(float(source.orthographic.xmag));
    c.ymag = std::abs(float(source.orthographic.ymag));
    if (!(c.xmag > 0.0f && c.ymag > 0.0f && std::isfinite(c.xmag) && std::isfinite(c.ymag)))
      reader.fail("orthographic camera has a zero or non-finite xmag/ymag");
    c.znear = float(source.orthographic.znear);
    c.zfar = float(source.orthographic.zfar);
  } else {
    c.yfov_radians = float(source.perspective.yfov);
    if (!(c.yfov_radians > 0.0f && c.yfov_radians < 3.1f)) reader.fail("perspective camera yfov is not in (0, pi)");
    c.znear = float(source.perspective.znear);
    c.zfar = source.perspective.zfar > 0 ? float(source.perspective.zfar) : c.znear * 1e4f;
  }
  if (!(c.znear > 0.0f || c.orthographic) || !(c.zfar > c.znear)) reader.fail("camera has an invalid depth range");
  return c;
}

// The buffers and images a .gltf names by URI are looked up without opening
// them (tinygltf's own check opens the file, which waits forever on a FIFO)
// and read with the same checks as the file itself.
bool referenced_file_exists(const std::string& path, void*) {
  std::error_code error;
  return std::filesystem::exists(path, error);
}

bool read_referenced_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  try {
    const std::string bytes = read_regular_file(path, kMaxSceneFileBytes);
    out->assign(bytes.begin(), bytes.end());
    return true;
  } catch (const std::invalid_argument& e) {
    if (err) *err += e.what();
    return false;
  }
}

// Parses `path` (.glb binary, anything else JSON), skipping images.
tinygltf::Model load_model(const std::string& path) {
  const std::string bytes = read_regular_file(path, kMaxSceneFileBytes);
  if (bytes.empty()) throw std::invalid_argument(path + ": cannot load glTF: the file is empty");
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skip_image, nullptr);
  loader.SetFsCallbacks({referenced_file_exists, tinygltf::ExpandFilePath, read_referenced_file,
                         tinygltf::WriteWholeFile, nullptr});
  tinygltf::Model model;
  std::string error, warning;
  std::string extension = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  const std::string base_dir = std::filesystem::path(path).parent_path().string();
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const bool ok = extension == ".glb"
                      ? loader.LoadBinaryFromMemory(&model, &error, &warning, data, unsigned(bytes.size()), base_dir)
                      : loader.LoadASCIIFromString(&model, &error, &warning, bytes.data(), unsigned(bytes.size()),
                                                   base_dir);
  if (!ok) throw std::invalid_argument(path + ": cannot load glTF: " + (error.empty() ? "unknown error" : error));
  return model;
}

// Flattens a glTF model into one Scene: every mesh instance in world space,
// one object per instance, the first camera found.
class SceneBuilder {
 public:
  SceneBuilder(const tinygltf::Model& model, const std::string& path)
      : model_(model), reader_(model, path), visited_(model.nodes.size(), 0) {
    scene_.name = path;
  }

  // Visits the default scene's roots, or, without scenes, every node that
  // is no other node's child.
  void visit_roots() {
    const int scene_index = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    if (model_.scenes.empty()) {
      std::vector<uint8_t> is_child(model_.nodes.size(), 0);
      for (const auto& node : model_.nodes)
        for (int child : node.children)
          if (child >= 0 && size_t(child) < is_child.size()) is_child[size_t(child)] = 1;
      for (size_t i = 0; i < model_.nodes.size(); ++i)
        if (!is_child[i]) visit(int(i), glm::mat4(1.0f), 0);
    } else {
      if (size_t(scene_index) >= model_.scenes.size()) reader_.fail("default scene index out of range");
      for (int root : model_.scenes[size_t(scene_index)].nodes) visit(root, glm::mat4(1.0f), 0);
    }
  }

  Scene finish() {
    if (scene_.indices.empty()) reader_.fail("contains no triangles");
    check_placement();
    scene_.object_count = next_object_;
    scene_.lit = !all_unlit_;
    scene_.camera = camera_ ? *camera_ : frame_bounding_sphere(scene_.bounds());
    scene_.validate();
    return std::move(scene_);
  }

 private:
  // glTF nodes form trees: a node reached twice (a cycle, or a node shared
  // by two parents, which could multiply into exponentially many visits) is
  // an error.
  void visit(int node_index, const glm::mat4& parent, int depth) {
    if (node_index < 0 || size_t(node_index) >= model_.nodes.size()) reader_.fail("node index out of range");
    if (depth > 256) reader_.fail("node hierarchy deeper than 256");
    if (visited_[size_t(node_index)]++)
      reader_.fail("node " + std::to_string(node_index) + " is reached twice (the node hierarchy must be a tree)");
    const auto& node = model_.nodes[size_t(node_index)];
    const glm::mat4 world = parent * local_transform(node);
    if (node.mesh >= 0) {
      if (size_t(node.mesh) >= model_.meshes.size()) reader_.fail("node mesh index out of range");
      add_mesh(model_.meshes[size_t(node.mesh)], world, node_index);
    }
    if (node.camera >= 0 && !camera_) {
      if (size_t(node.camera) >= model_.cameras.size()) reader_.fail("node camera index out of range");
      camera_ = read_camera(model_.cameras[size_t(node.camera)], world, reader_);
    }
    for (int child : node.children) visit(child, world, depth + 1);
  }

  void add_mesh(const tinygltf::Mesh& mesh, const glm::mat4& world, int node_index) {
    const uint32_t object = next_object_++;
    const size_t first_vertex = scene_.vertices.size();
    for (const auto& primitive : mesh.primitives) add_primitive(mesh, primitive, world, object);
    placed_.push_back(measure_node(node_index, first_vertex));
  }

  void add_primitive(const tinygltf::Mesh& mesh, const tinygltf::Primitive& primitive, const glm::mat4& world,
                     uint32_t object) {
    if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != -1)
      reader_.fail("mesh '" + mesh.name + "' has a primitive of mode " + std::to_string(primitive.mode) +
                   "; only triangles are supported");
    auto position_it = primitive.attributes.find("POSITION");
    if (position_it == primitive.attributes.end()) reader_.fail("mesh '" + mesh.name + "' has no POSITION");
    const auto positions = reader_.read(position_it->second, 3);
    // The file's own values; what the node transforms make of them is checked in check_placement.
    for (size_t i = 0; i < positions.size(); ++i)
      if (!std::isfinite(positions[i]) || std::abs(positions[i]) > double(FLT_MAX))
        reader_.fail("mesh '" + mesh.name + "' vertex " + std::to_string(i / 3) + " has a non-finite position");
    const size_t vertex_count = positions.size() / 3;
    std::vector<double> normals;
    if (auto it = primitive.attributes.find("NORMAL"); it != primitive.attributes.end()) {
      normals = reader_.read(it->second, 3);
      if (normals.size() != positions.size()) reader_.fail("mesh '" + mesh.name + "' NORMAL count differs from POSITION");
    }
    const std::vector<uint32_t> indices = primitive_indices(mesh, primitive, vertex_count);
    if (scene_.vertices.size() + vertex_count > kMaxVertices ||
        scene_.indices.size() / 3 + indices.size() / 3 > kMaxTriangles)
      reader_.fail("the instanced scene has more than " + std::to_string(kMaxVertices) + " vertices or " +
                   std::to_string(kMaxTriangles) + " triangles");
    const glm::vec4 color = material_color(primitive.material);
    const auto base = uint32_t(scene_.vertices.size());
    add_vertices(positions, normals, world, color, object);
    add_triangles(base, indices, normals.empty());
  }

  // The primitive's indices (0..n-1 without an index accessor), each
  // checked against its vertex count, in whole triangles.
  std::vector<uint32_t> primitive_indices(const tinygltf::Mesh& mesh, const tinygltf::Primitive& primitive,
                                          size_t vertex_count) const {
    std::vector<uint32_t> indices;
    if (primitive.indices >= 0) {
      if (size_t(primitive.indices) < model_.accessors.size()) {
        const int type = model_.accessors[size_t(primitive.indices)].componentType;
        if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
          reader_.fail("mesh '" + mesh.name + "' indices are not unsigned byte, short or int");
      }
      for (double i : reader_.read(primitive.indices, 1)) {
        if (i >= double(vertex_count))
          reader_.fail("mesh '" + mesh.name + "' index " + std::to_string(uint64_t(i)) + " is past its " +
                       std::to_string(vertex_count) + " vertices");
        indices.push_back(uint32_t(i));
      }
    } else {
      for (uint32_t i = 0; i < vertex_count; ++i) indices.push_back(i);
    }
    if (indices.size() % 3 != 0) reader_.fail("mesh '" + mesh.name + "' index count is not a multiple of 3");
    return indices;
  }

  // The primitive's vertices in world space; normals through the normal
  // matrix, or zero to be accumulated by add_triangles when there are none.
  void add_vertices(const std::vector<double>& positions, const std::vector<double>& normals, const glm::mat4& world,
                    const glm::vec4& color, uint32_t object) {
    const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(world)));
    for (size_t i = 0; i < positions.size() / 3; ++i) {
      Vertex v;
      v.position = glm::vec3(world * glm::vec4(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2], 1.0));
      v.normal = glm::vec3(0.0f);
      if (!normals.empty()) {
        // A zero or non-finite file normal must not become NaN shading.
        const glm::vec3 n = normal_matrix * glm::vec3(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
        const float length = glm::length(n);
        v.normal = std::isfinite(length) && length > 0.0f ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
      }
      v.color = color;
      v.object_id = object;
      v.surface_id = object;
      scene_.vertices.push_back(v);
    }
  }

  // The triangles of vertices from `base` on; with `face_normals` (the file
  // has none) each vertex's normal is its faces' area-weighted sum.
  void add_triangles(uint32_t base, const std::vector<uint32_t>& indices, bool face_normals) {
    std::vector<Vertex>& vertices = scene_.vertices;
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
      const uint32_t a = base + indices[t], b = base + indices[t + 1], c = base + indices[t + 2];
      if (face_normals) {
        // In double: the cross product of a large model's edges squares
        // their length, and its length squares it again (NaN in float).
        const glm::dvec3 pa(vertices[a].position), n = glm::cross(glm::dvec3(vertices[b].position) - pa,
                                                                   glm::dvec3(vertices[c].position) - pa);
        accumulated_normals_.resize(vertices.size());
        for (uint32_t k : {a, b, c}) accumulated_normals_[k] += n;
      }
      scene_.indices.insert(scene_.indices.end(), {a, b, c});
      scene_.triangle_ids.push_back(uint32_t(scene_.triangle_ids.size()));
    }
    if (!face_normals) return;
    accumulated_normals_.resize(vertices.size());
    for (size_t i = base; i < vertices.size(); ++i) {
      const glm::dvec3 n = accumulated_normals_[i];
      const double length = glm::length(n);
      vertices[i].normal = std::isfinite(length) && length > 0.0 ? glm::vec3(n / length) : glm::vec3(0.0f, 0.0f, 1.0f);
    }
  }

  glm::vec4 material_color(int material_index) {
    if (material_index < 0) {
      all_unlit_ = false;
      return glm::vec4(1.0f);
    }
    if (size_t(material_index) >= model_.materials.size()) reader_.fail("material index out of range");
    const auto& material = model_.materials[size_t(material_index)];
    if (!material.extensions.count("KHR_materials_unlit")) all_unlit_ = false;
    const auto& f = material.pbrMetallicRoughness.baseColorFactor;
    glm::vec4 color(1.0f);
    if (f.size() == 4) color = glm::vec4(float(f[0]), float(f[1]), float(f[2]), float(f[3]));
    for (int c = 0; c < 4; ++c) {
      if (!std::isfinite(color[c]))
        reader_.fail("material " + std::to_string(material_index) + " has a non-finite baseColorFactor");
      color[c] = std::clamp(color[c], 0.0f, 1.0f);  // the spec's range; blending assumes it
    }
    // MASK: the colour has no texture, so the whole triangle is either
    // kept opaque or fully transparent by the cutoff. BLEND keeps alpha.
    if (material.alphaMode == "OPAQUE" || material.alphaMode.empty()) color.a = 1.0f;
    else if (material.alphaMode == "MASK") color.a = color.a >= float(material.alphaCutoff) ? 1.0f : 0.0f;
    return color;
  }

  // Where one mesh node put its vertices, for the checks of the scene's size.
  struct PlacedNode {
    int node;
    glm::dvec3 lo, hi;
    double farthest;  // the largest |coordinate|; infinite when one is not finite
    double extent() const { return lo.x <= hi.x ? glm::length(hi - lo) : 0.0; }
  };

  PlacedNode measure_node(int node_index, size_t first_vertex) const {
    PlacedNode placed{node_index, glm::dvec3(INFINITY), glm::dvec3(-INFINITY), 0.0};
    for (size_t i = first_vertex; i < scene_.vertices.size(); ++i) {
      const glm::dvec3 p(scene_.vertices[i].position);
      placed.lo = glm::min(placed.lo, p);
      placed.hi = glm::max(placed.hi, p);
      for (int axis = 0; axis < 3; ++axis)
        placed.farthest = std::isfinite(p[axis]) ? std::max(placed.farthest, std::abs(p[axis])) : INFINITY;
    }
    return placed;
  }

  std::string node_name(int node_index) const {
    const std::string& name = model_.nodes[size_t(node_index)].name;
    return "node " + std::to_string(node_index) + (name.empty() ? "" : " '" + name + "'");
  }

  // The node transforms must leave a scene that float rendering can draw:
  // finite, within kLargestCoordinate, at least kSmallestExtent across, and
  // not so far from the origin that float positions cannot resolve it.
  void check_placement() const {
    const auto by = [](auto measure) {
      return [measure](const PlacedNode& a, const PlacedNode& b) { return measure(a) < measure(b); };
    };
    const PlacedNode& farthest = *std::max_element(placed_.begin(), placed_.end(),
                                                   by([](const PlacedNode& p) { return p.farthest; }));
    const std::string through = " through its scale, matrix or translation (or its parents'): ";
    char text[256];
    if (!std::isfinite(farthest.farthest))
      reader_.fail(node_name(farthest.node) + " makes vertex positions non-finite" + through + "scale the model down");
    if (!(farthest.farthest <= kLargestCoordinate)) {
      std::snprintf(text, sizeof text, "puts vertices %.3g from the origin, beyond the %.0e that rendering in float "
                    "handles,", farthest.farthest, kLargestCoordinate);
      reader_.fail(node_name(farthest.node) + " " + text + through + "scale the model down");
    }
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (const PlacedNode& p : placed_)
      if (p.lo.x <= p.hi.x) lo = glm::min(lo, p.lo), hi = glm::max(hi, p.hi);  // a node with vertices
    const double extent = lo.x <= hi.x ? glm::length(hi - lo) : 0.0;
    const PlacedNode& largest =
        *std::max_element(placed_.begin(), placed_.end(), by([](const PlacedNode& p) { return p.extent(); }));
    if (!(extent >= kSmallestExtent)) {
      std::snprintf(text, sizeof text, "spans %.3g, less than the %.0e that rendering in float resolves,", extent,
                    kSmallestExtent);
      reader_.fail("the scene " + std::string(text) + " and its largest part, " + node_name(largest.node) +
                   ", is that small" + through + "scale the model up");
    }
    const double step = farthest.farthest * std::ldexp(1.0, -23);  // float spacing at that distance
    if (extent < kLeastStepsAcross * step) {
      std::snprintf(text, sizeof text, "puts vertices %.3g from the origin, where float positions are %.3g apart, "
                    "while the whole scene spans only %.3g,", farthest.farthest, step, extent);
      reader_.fail(node_name(farthest.node) + " " + text + through + "move it nearer the origin");
    }
  }

  const tinygltf::Model& model_;
  GltfReader reader_;
  std::vector<uint8_t> visited_;
  std::vector<PlacedNode> placed_;
  std::vector<glm::dvec3> accumulated_normals_;
  Scene scene_;
  bool all_unlit_ = true;
  std::optional<Camera> camera_;
  uint32_t next_object_ = 0;
};

}  // namespace

Scene load_gltf_scene(const std::string& path) {
  const tinygltf::Model model = load_model(path);
  SceneBuilder builder(model, path);
  builder.visit_roots();
  return builder.finish();
}

}  // namespace oit
