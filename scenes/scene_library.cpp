#include "scene_library.h"

#include <filesystem>
#include <stdexcept>

#include "gltf_loader.h"
#include "parametric.h"
#include "stacked_quads.h"

namespace oit {

const std::vector<SceneDescriptor>& scene_library() {
  static const std::vector<SceneDescriptor> library = {
      {"quads",
       "murray2016 section 6: full-screen quads at random depths with random object ids (orthographic, unlit)",
       {ParamSpec::integer("layers", 32, 1, 4096, "number of stacked quads = fragments per pixel"),
        ParamSpec::integer("objects", 32, 1, 65535, "object ids are drawn from [0, objects)"),
        ParamSpec::integer("seed", 1, 0, 4294967295ll, "random seed for depths, colours and object ids"),
        ParamSpec::real("alpha", 0.3, 0.0, 1.0, "opacity of every quad")},
       [](const ParamSet& p) {
         StackedQuadsParams q;
         q.layers = int(p.integer("layers"));
         q.objects = int(p.integer("objects"));
         q.seed = uint32_t(p.integer("seed"));
         q.alpha = float(p.real("alpha"));
         return make_stacked_quads(q);
       }},
      {"spheres",
       "closed UV spheres on a ring, overlapping on screen and in depth (perspective, lit): "
       "depth complexity varies per pixel",
       {ParamSpec::integer("count", 3, 1, 64, "number of spheres"),
        ParamSpec::integer("slices", 32, 3, 4096, "segments around each sphere"),
        ParamSpec::integer("stacks", 16, 2, 4096, "segments from pole to pole"),
        ParamSpec::real("alpha", 0.4, 0.0, 1.0, "opacity of every sphere")},
       [](const ParamSet& p) {
         OverlappingSpheresParams s;
         s.count = int(p.integer("count"));
         s.slices = int(p.integer("slices"));
         s.stacks = int(p.integer("stacks"));
         s.alpha = float(p.real("alpha"));
         return make_overlapping_spheres(s);
       }},
  };
  return library;
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
  const std::filesystem::path path(spec);
  const std::string extension = path.extension().string();
  if (extension == ".gltf" || extension == ".glb") {
    if (!params.empty()) throw std::invalid_argument("scene file '" + spec + "' takes no scene parameters");
    if (!std::filesystem::exists(path)) throw std::invalid_argument("scene file '" + spec + "' does not exist");
    return load_gltf_scene(spec);
  }
  std::string names;
  for (const auto& descriptor : scene_library()) names += (names.empty() ? "" : ", ") + descriptor.id;
  throw std::invalid_argument("unknown scene '" + spec + "': expected one of " + names + " or a .gltf/.glb file");
}

}  // namespace oit
