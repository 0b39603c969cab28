#include "scenes/scene_library.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <stdexcept>

#include "base/suggest.h"
#include "scenes/gltf_loader.h"
#include "scenes/mesh_loader.h"
#include "scenes/model_files.h"
#include "scenes/parametric.h"
#include "scenes/random_scenes.h"
#include "scenes/stacked_quads.h"
#include "scenes/stress_layers.h"

namespace oit {
namespace {

// count 0: a single surface, no `count` parameter.
ParamSchema surface_params(int count) {
  ParamSchema schema = {ParamSpec::integer("slices", 64, 3, 4096, "segments around"),
                        ParamSpec::integer("stacks", 32, 3, 4096, "segments along"),
                        ParamSpec::real("alpha", 0.4, 0.0, 1.0, "opacity of every surface")};
  if (count > 0) schema.insert(schema.begin(), ParamSpec::integer("count", count, 1, 64, "number of surfaces"));
  return schema;
}

SurfaceParams surface(const ParamSet& p) {
  SurfaceParams s;
  const auto& values = p.values();
  s.count = std::any_of(values.begin(), values.end(), [](const auto& v) { return v.first == "count"; })
                ? int(p.integer("count"))
                : 1;
  s.slices = int(p.integer("slices"));
  s.stacks = int(p.integer("stacks"));
  s.alpha = float(p.real("alpha"));
  return s;
}

bool is_gltf_file(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".gltf" || extension == ".glb";
}

Scene load_scene_file(const std::string& path) {
  if (!std::filesystem::exists(path)) throw std::invalid_argument("scene file '" + path + "' does not exist");
  return is_gltf_file(path) ? load_gltf_scene(path) : load_mesh_scene(path);
}

std::vector<std::string> model_names() {
  std::vector<std::string> names;
  for (const auto& model : model_files()) names.push_back(model.name);
  return names;
}

std::string model_descriptions() {
  std::string text;
  for (const auto& model : model_files()) text += "; " + model.name + ": " + model.description + " [" + model.package + "]";
  return text;
}

// The scenes' factories: their validated parameters into the generator's.
Scene make_quads_scene(const ParamSet& p) {
  StackedQuadsParams q;
  q.layers = int(p.integer("layers"));
  q.objects = int(p.integer("objects"));
  q.seed = uint32_t(p.integer("seed"));
  q.alpha = float(p.real("alpha"));
  return make_stacked_quads(q);
}

Scene make_random_quads_scene(const ParamSet& p) {
  RandomQuadsParams q;
  q.count = int(p.integer("count"));
  q.size = float(p.real("size"));
  q.seed = uint32_t(p.integer("seed"));
  q.alpha = float(p.real("alpha"));
  q.order = p.choice("order");
  return make_random_quads(q);
}

Scene make_particles_scene(const ParamSet& p) {
  ParticlesParams q;
  q.per_axis = int(p.integer("per_axis"));
  q.slices = int(p.integer("slices"));
  q.stacks = int(p.integer("stacks"));
  q.alpha = float(p.real("alpha"));
  q.seed = uint32_t(p.integer("seed"));
  return make_particles(q);
}

// A model file with every triangle's opacity replaced by `alpha`.
Scene make_model_scene(const ParamSet& p) {
  Scene scene = load_scene_file(model_path(p.choice("name")));
  scene.name = "model";
  for (Vertex& v : scene.vertices) v.color.a = float(p.real("alpha"));
  return scene;
}

}  // namespace

StressLayersParams stress_layers_params(const ParamSet& p) {
  StressLayersParams s;
  s.layers = int(p.integer("layers"));
  s.gap = p.real("gap");
  s.space = p.choice("space");
  s.near_far_ratio = p.real("near_far_ratio");
  s.alpha = float(p.real("alpha"));
  s.alpha_mode = p.choice("alpha_mode");
  s.extra = p.choice("extra");
  s.seed = uint32_t(p.integer("seed"));
  return s;
}

const std::vector<SceneDescriptor>& scene_library() {
  static const std::vector<SceneDescriptor> library = {
      {"quads",
       "murray2016 section 6: full-screen quads at random depths with random object ids (orthographic, unlit)",
       {ParamSpec::integer("layers", 32, 1, 4096, "number of stacked quads = fragments per pixel"),
        ParamSpec::integer("objects", 32, 1, 65535, "object ids are drawn from [0, objects)"),
        ParamSpec::integer("seed", 1, 0, 4294967295ll, "random seed for depths, colours and object ids"),
        ParamSpec::real("alpha", 0.3, 0.0, 1.0, "opacity of every quad")},
       make_quads_scene},
      {"spheres",
       "closed UV spheres on a ring, overlapping on screen and in depth (perspective, lit): "
       "depth complexity varies per pixel",
       {ParamSpec::integer("count", 3, 1, 64, "number of spheres"),
        ParamSpec::integer("slices", 32, 3, 4096, "segments around each sphere"),
        ParamSpec::integer("stacks", 16, 2, 4096, "segments from pole to pole"),
        ParamSpec::real("alpha", 0.4, 0.0, 1.0, "opacity of every sphere")},
       [](const ParamSet& p) { return make_overlapping_spheres(surface(p)); }},
      {"torus", "one torus tilted towards the viewer: up to 4 layers, positive and negative curvature (lit)",
       surface_params(0), [](const ParamSet& p) { return make_torus(surface(p)); }},
      {"nested_spheres", "concentric spheres of radii 1 .. 1/count: 2*count layers at the centre (lit)",
       surface_params(3), [](const ParamSet& p) { return make_nested_spheres(surface(p)); }},
      {"cylinders", "concentric open cylinders seen from above at an angle, carnecky2013 Fig. 2 (lit)",
       surface_params(3), [](const ParamSet& p) { return make_concentric_cylinders(surface(p)); }},
      {"random_quads",
       "screen-aligned quads at random positions and distinct depths (orthographic, unlit); "
       "depth complexity about count*size^2",
       {ParamSpec::integer("count", 64, 1, 4096, "number of quads"),
        ParamSpec::real("size", 0.5, 0.01, 2.0, "side of each quad as a fraction of the view width"),
        ParamSpec::integer("seed", 1, 0, 4294967295ll, "random seed"),
        ParamSpec::real("alpha", 0.3, 0.0, 1.0, "opacity of every quad"),
        ParamSpec::choice("order", "random", {"random", "front_to_back", "back_to_front"}, "submission order")},
       make_random_quads_scene},
      {"particles", "per_axis^3 small separate spheres on a jittered grid, one object id each (lit)",
       {ParamSpec::integer("per_axis", 6, 1, 40, "spheres along each axis"),
        ParamSpec::integer("slices", 8, 3, 256, "segments around each sphere"),
        ParamSpec::integer("stacks", 6, 2, 256, "segments from pole to pole"),
        ParamSpec::real("alpha", 0.5, 0.0, 1.0, "opacity of every sphere"),
        ParamSpec::integer("seed", 1, 0, 4294967295ll, "random seed")},
       make_particles_scene},
      {"stress_layers",
       "full-screen layers for numerical stress: tiny depth gaps (ndc or relative eye depth under a perspective "
       "camera), coplanar layers (gap 0), extreme alphas, degenerate extras; exact image known in closed form",
       {ParamSpec::integer("layers", 8, 1, 4096, "number of layers"),
        ParamSpec::real("gap", 1e-3, 0.0, 1.0, "depth gap between consecutive layers (0: coplanar)"),
        ParamSpec::choice("space", "ndc", {"ndc", "eye"},
                          "ndc: gap in NDC under an orthographic camera; eye: gap relative to eye depth, perspective"),
        ParamSpec::real("near_far_ratio", 100.0, 1.01, 1e7, "perspective far/near (space=eye)"),
        ParamSpec::real("alpha", 0.5, 0.0, 1.0, "opacity of every layer (alpha_mode=constant)"),
        ParamSpec::choice("alpha_mode", "constant", {"constant", "mixed"}, "mixed cycles 1, alpha, 1e-4, 0.5"),
        ParamSpec::choice("extra", "none", {"none", "zero_area", "nan_vertex", "inf_vertex", "empty"},
                          "degenerate addition"),
        ParamSpec::integer("seed", 1, 0, 4294967295ll, "shuffle of the submission order")},
       [](const ParamSet& p) { return make_stress_layers(stress_layers_params(p)); }},
      {"model",
       "a real model from a Debian package (see setup.sh), every triangle given the opacity `alpha`" +
           model_descriptions(),
       {ParamSpec::choice("name", "bunny", model_names(), "which model"),
        ParamSpec::real("alpha", 0.4, 0.0, 1.0, "opacity of every triangle (replaces the file's own)")},
       make_model_scene},
  };
  return library;
}

namespace {

// A spec that is no library scene must be a scene file, without parameters.
void check_scene_file_spec(const std::string& spec, const RawParams& params) {
  if (is_gltf_file(spec) || is_mesh_file(spec)) {
    if (!params.empty()) throw std::invalid_argument("scene file '" + spec + "' takes no scene parameters");
    return;
  }
  std::vector<std::string> ids;
  std::string names;
  for (const auto& descriptor : scene_library()) {
    ids.push_back(descriptor.id);
    names += (names.empty() ? "" : ", ") + descriptor.id;
  }
  throw std::invalid_argument("unknown scene '" + spec + "'" + did_you_mean(spec, ids) + " (expected one of " + names +
                              " or a .gltf/.glb/.obj/.off/.ply/.stl file)");
}

}  // namespace

std::string canonical_scene_params(const std::string& spec, const RawParams& params) {
  for (const auto& descriptor : scene_library())
    if (descriptor.id == spec) return ParamSet(descriptor.params, params, "scene '" + spec + "'").canonical();
  check_scene_file_spec(spec, params);
  return "";
}

Scene load_scene(const std::string& spec, const RawParams& params) {
  for (const auto& descriptor : scene_library()) {
    if (descriptor.id != spec) continue;
    ParamSet values(descriptor.params, params, "scene '" + spec + "'");
    Scene scene = descriptor.make(values);
    scene.params = values.canonical();
    scene.validate();
    return scene;
  }
  check_scene_file_spec(spec, params);
  return load_scene_file(spec);
}

}  // namespace oit
