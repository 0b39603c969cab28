#pragma once
// Real models from Debian packages, addressed by short names (the `model`
// scene). Nothing is committed: setup.sh installs the packages (and unpacks
// the optional CGAL meshes into <build>/models/cgal); a missing model is an
// error naming the package that provides it.
#include <string>
#include <vector>

namespace oit {

struct ModelFile {
  std::string name;         // the `name` parameter of the `model` scene
  std::string file;         // absolute, or relative to the model cache directory
  std::string package;      // Debian package that provides it
  std::string description;
  bool in_model_cache = false;  // unpacked by setup.sh rather than installed by apt
};

const std::vector<ModelFile>& model_files();

// Where unpacked models live: $OIT_MODEL_DIR, else <build>/models.
std::string model_cache_dir();

// The installed path of a model; throws std::invalid_argument naming the
// model, the path and the package when it is not there.
std::string model_path(const std::string& name);

}  // namespace oit
