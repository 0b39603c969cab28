#pragma once
// Real models from Debian packages, addressed by short names (the `model`
// scene). Nothing is committed: setup.sh installs the packages (and unpacks
// the optional CGAL meshes into <build>/models/cgal); a missing model is an
// error naming the package that provides it.
#include <stdexcept>
#include <string>
#include <vector>

namespace oit {

struct ModelFile {
  std::string name;         // the `name` parameter of the `model` scene
  std::string file;         // absolute, or relative to the model cache directory
  std::string package;      // the Debian or npm package that provides it
  std::string description;
  bool in_model_cache = false;  // unpacked by setup.sh rather than installed by apt
};

const std::vector<ModelFile>& model_files();

// Where unpacked models live: $OIT_MODEL_DIR, else <build>/models.
std::string model_cache_dir();

// An optional model that is not installed: runs that need it are skipped,
// not failed (the message names the package that provides it).
struct MissingModel : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// The installed path of a model; throws MissingModel naming the model, the
// path and the package when it is not there, std::invalid_argument for an
// unknown name.
std::string model_path(const std::string& name);

}  // namespace oit
