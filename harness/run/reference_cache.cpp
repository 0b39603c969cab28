#include "harness/run/reference_cache.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string_view>

#include "harness/output/output_file.h"
#include "scenes/regular_file.h"

#include "harness/gl/embedded_shaders.h"
#include "oit_revision.h"

namespace oit {
namespace {

// Version 2 ends in a checksum of everything before it.
constexpr char kMagic[8] = {'O', 'I', 'T', 'R', 'E', 'F', '2', '\n'};

uint64_t fnv1a(std::string_view text, uint64_t hash = 1469598103934665603ull) {
  for (unsigned char c : text) hash = (hash ^ c) * 1099511628211ull;
  return hash;
}

template <typename T>
void put(std::string& bytes, const T& value) {
  bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
}

// Every embedded shader takes part: the reference's own and the shared ones
// it includes (shading, bindings).
uint64_t shader_sources_hash() {
  static const uint64_t hash = [] {
    uint64_t h = 1469598103934665603ull;
    for (const auto& [path, source] : embedded_shader_sources()) h = fnv1a(source, fnv1a(path, h));
    return h;
  }();
  return hash;
}

}  // namespace

ReferenceCache::ReferenceCache(std::string directory) : directory_(std::move(directory)) {}

ReferenceCache ReferenceCache::from_environment() {
  if (const char* dir = std::getenv("OIT_REFERENCE_CACHE"); dir && *dir)
    return ReferenceCache(std::string(dir) == "off" ? "" : dir);
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return ReferenceCache(std::string(xdg) + "/oitbench/references");
  if (const char* home = std::getenv("HOME"); home && *home)
    return ReferenceCache(std::string(home) + "/.cache/oitbench/references");
  return ReferenceCache("");
}

std::string ReferenceCache::path_for(const std::string& key) const {
  char name[64];
  std::snprintf(name, sizeof name, "%016llx.oitref",
                static_cast<unsigned long long>(fnv1a(key + "|" + OIT_GIT_REVISION, shader_sources_hash())));
  return directory_ + "/" + name;
}

namespace {

// Sizes of an entry's parts around its key and payload.
constexpr uint64_t kKeyStart = sizeof kMagic + sizeof(uint32_t);
constexpr uint64_t kSizesBytes = 2 * sizeof(int32_t), kChecksumBytes = sizeof(uint64_t);
constexpr int32_t kLargestSide = 16384;

// The image of the entry in `file`, or why it is not usable. Every size
// the header declares is checked against the file's length before anything
// is allocated from it.
std::optional<Image> read_entry(const RegularFile& file, const std::string& key, int width, int height,
                                std::string& problem) {
  const uint64_t size = file.size();
  if (size < kKeyStart + kSizesBytes + kChecksumBytes) {
    problem = "is " + std::to_string(size) + " bytes, too short for an entry";
    return std::nullopt;
  }
  const std::string start = file.read(0, kKeyStart);
  uint32_t key_length = 0;
  std::memcpy(&key_length, start.data() + sizeof kMagic, sizeof key_length);
  if (std::memcmp(start.data(), kMagic, sizeof kMagic) != 0) {
    problem = "is not an entry of this version of the cache (another header)";
    return std::nullopt;
  }
  if (key_length != key.size() || size < kKeyStart + key_length + kSizesBytes + kChecksumBytes ||
      file.read(kKeyStart, key_length) != key) {
    problem = "holds the reference of another key (a hash collision or a foreign file)";
    return std::nullopt;
  }
  int32_t sizes[2] = {0, 0};
  std::memcpy(sizes, file.read(kKeyStart + key_length, kSizesBytes).data(), kSizesBytes);
  const uint64_t payload_start = kKeyStart + key_length + kSizesBytes;
  if (sizes[0] < 1 || sizes[1] < 1 || sizes[0] > kLargestSide || sizes[1] > kLargestSide ||
      size != payload_start + uint64_t(sizes[0]) * uint64_t(sizes[1]) * 4 * sizeof(float) + kChecksumBytes) {
    problem = "is " + std::to_string(size) + " bytes, which does not fit the " + std::to_string(sizes[0]) + "x" +
              std::to_string(sizes[1]) + " image its header declares";
    return std::nullopt;
  }
  if ((width > 0 && sizes[0] != width) || (height > 0 && sizes[1] != height)) {
    problem = "holds a " + std::to_string(sizes[0]) + "x" + std::to_string(sizes[1]) + " image where " +
              std::to_string(width) + "x" + std::to_string(height) + " is needed";
    return std::nullopt;
  }
  // A flipped byte or a payload written by anything else fails the checksum.
  const std::string bytes = file.read(0, size);
  uint64_t checksum = 0;
  std::memcpy(&checksum, bytes.data() + size - kChecksumBytes, kChecksumBytes);
  if (fnv1a(std::string_view(bytes).substr(0, size - kChecksumBytes)) != checksum) {
    problem = "fails its checksum (damaged)";
    return std::nullopt;
  }
  Image image{sizes[0], sizes[1], std::vector<float>(size_t(sizes[0]) * size_t(sizes[1]) * 4)};
  std::memcpy(image.rgba.data(), bytes.data() + payload_start, image.rgba.size() * sizeof(float));
  // The exact reference is a blend of finite colours: anything else is damage.
  if (!std::all_of(image.rgba.begin(), image.rgba.end(), [](float v) { return std::isfinite(v); })) {
    problem = "holds non-finite values (damaged)";
    return std::nullopt;
  }
  return image;
}

}  // namespace

std::optional<Image> ReferenceCache::load(const std::string& key, int width, int height) const {
  if (!enabled()) return std::nullopt;
  const std::string path = path_for(key);
  struct stat info{};
  if (::lstat(path.c_str(), &info) != 0 && errno == ENOENT) return std::nullopt;  // the ordinary miss
  std::string problem;
  try {
    const RegularFile file(path);  // a FIFO, a device or a directory is refused without reading it
    if (auto image = read_entry(file, key, width, height, problem)) return image;
    problem = "'" + path + "' " + problem + "; it is replaced by the reference rendered again";
  } catch (const std::invalid_argument& e) {
    problem = std::string(e.what()) + "; the reference is rendered again (remove it to let the cache keep one)";
  }
  std::fprintf(stderr, "oitbench: reference cache entry not used: %s\n", problem.c_str());
  return std::nullopt;
}

void ReferenceCache::store(const std::string& key, const Image& image) const {
  if (!enabled()) return;
  std::string bytes(kMagic, sizeof kMagic);
  put(bytes, uint32_t(key.size()));
  bytes += key;
  put(bytes, int32_t(image.width));
  put(bytes, int32_t(image.height));
  bytes.append(reinterpret_cast<const char*>(image.rgba.data()), image.rgba.size() * sizeof(float));
  put(bytes, fnv1a(bytes));
  try {
    write_file_atomically(path_for(key), bytes);
  } catch (const std::exception& e) {
    // The run itself is whole without the cache; the next one renders again.
    std::fprintf(stderr, "oitbench: reference cache not written (the reference will be rendered again next "
                         "time): %s\n", e.what());
  }
}

}  // namespace oit
