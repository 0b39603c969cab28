// libFuzzer target: arbitrary bytes as a scene file of one format (the
// extension is a compile definition). A loader may accept the bytes or
// reject them with std::invalid_argument; anything else -- another
// exception, a crash, a sanitizer report, a hang (libFuzzer's -timeout) or
// an allocation above -rss_limit_mb -- is a finding.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>

#include "scenes/scene_library.h"

namespace {

// The loaders read files (OpenMesh and tinygltf open paths), so each input
// goes through one file per process.
const std::string& input_path() {
  static const std::string path = "/tmp/oit_fuzz_" + std::to_string(getpid()) + OIT_FUZZ_EXTENSION;
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  {
    std::ofstream out(input_path(), std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  try {
    const oit::Scene scene = oit::load_scene(input_path(), {});
    if (scene.triangle_count() == 0) {
      std::fprintf(stderr, "loaded a scene without triangles\n");
      std::abort();
    }
  } catch (const std::invalid_argument&) {
    // A clean rejection.
  }
  return 0;
}
