#include "core/reference_cache.h"

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "gl/embedded_shaders.h"
#include "oit_revision.h"

namespace oit {
namespace {

constexpr char kMagic[8] = {'O', 'I', 'T', 'R', 'E', 'F', '1', '\n'};

uint64_t fnv1a(const std::string& text, uint64_t hash = 1469598103934665603ull) {
  for (unsigned char c : text) hash = (hash ^ c) * 1099511628211ull;
  return hash;
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
  char magic[8];
  int32_t size[2];
  uint32_t key_length = 0;
  if (!in.read(magic, 8) || std::memcmp(magic, kMagic, 8) != 0) return std::nullopt;
  if (!in.read(reinterpret_cast<char*>(&key_length), 4) || key_length > 1 << 20) return std::nullopt;
  std::string stored_key(key_length, '\0');
  if (!in.read(stored_key.data(), key_length) || stored_key != key) return std::nullopt;  // hash collision
  if (!in.read(reinterpret_cast<char*>(size), sizeof size)) return std::nullopt;
  if (size[0] < 1 || size[1] < 1 || size[0] > 16384 || size[1] > 16384) return std::nullopt;
  Image image{size[0], size[1], std::vector<float>(size_t(size[0]) * size_t(size[1]) * 4)};
  if (!in.read(reinterpret_cast<char*>(image.rgba.data()), std::streamsize(image.rgba.size() * 4))) return std::nullopt;
  return image;
}

void ReferenceCache::store(const std::string& key, const Image& image) const {
  if (!enabled()) return;
  std::error_code error;
  std::filesystem::create_directories(directory_, error);
  const std::string path = path_for(key);
  const std::string temporary = path + ".tmp" + std::to_string(getpid());
  {
    std::ofstream out(temporary, std::ios::binary);
    const auto key_length = uint32_t(key.size());
    const int32_t size[2] = {image.width, image.height};
    out.write(kMagic, 8);
    out.write(reinterpret_cast<const char*>(&key_length), 4);
    out.write(key.data(), std::streamsize(key.size()));
    out.write(reinterpret_cast<const char*>(size), sizeof size);
    out.write(reinterpret_cast<const char*>(image.rgba.data()), std::streamsize(image.rgba.size() * 4));
    if (!out) {
      std::filesystem::remove(temporary, error);
      return;
    }
  }
  std::filesystem::rename(temporary, path, error);
}

}  // namespace oit
