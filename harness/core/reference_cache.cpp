#include "harness/core/reference_cache.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string_view>

#include "harness/core/output_file.h"

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

// Reads a T at `offset` and moves past it; false when the bytes run out.
template <typename T>
bool take(std::string_view bytes, size_t& offset, T& value) {
  if (bytes.size() - offset < sizeof value) return false;
  std::memcpy(&value, bytes.data() + offset, sizeof value);
  offset += sizeof value;
  return true;
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

std::optional<Image> ReferenceCache::load(const std::string& key) const {
  if (!enabled()) return std::nullopt;
  std::ifstream in(path_for(key), std::ios::binary);
  if (!in) return std::nullopt;
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // A flipped byte, a cut or a payload written by anything else fails the checksum.
  uint64_t checksum = 0;
  size_t offset = bytes.size() - std::min(bytes.size(), sizeof checksum);
  if (!take(std::string_view(bytes), offset, checksum) ||
      fnv1a(std::string_view(bytes).substr(0, bytes.size() - sizeof checksum)) != checksum)
    return std::nullopt;
  const std::string_view body(bytes.data(), bytes.size() - sizeof checksum);
  offset = sizeof kMagic;
  uint32_t key_length = 0;
  int32_t width = 0, height = 0;
  if (body.size() < sizeof kMagic || std::memcmp(body.data(), kMagic, sizeof kMagic) != 0) return std::nullopt;
  if (!take(body, offset, key_length) || body.size() - offset < key_length) return std::nullopt;
  if (body.substr(offset, key_length) != key) return std::nullopt;  // hash collision
  offset += key_length;
  if (!take(body, offset, width) || !take(body, offset, height)) return std::nullopt;
  if (width < 1 || height < 1 || width > 16384 || height > 16384) return std::nullopt;
  Image image{width, height, std::vector<float>(size_t(width) * size_t(height) * 4)};
  if (body.size() - offset != image.rgba.size() * sizeof(float)) return std::nullopt;
  std::memcpy(image.rgba.data(), body.data() + offset, body.size() - offset);
  // The exact reference is a blend of finite colours: anything else is damage.
  for (float v : image.rgba)
    if (!std::isfinite(v)) return std::nullopt;
  return image;
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
