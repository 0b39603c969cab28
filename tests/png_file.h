#pragma once
// A PNG read back for tests (stb_image, 8-bit RGBA, top row first): what
// the written file holds, as an image viewer would see it.
#include <stb_image.h>

#include <string>
#include <vector>

namespace oit::test {

struct Png {
  int width = 0, height = 0;
  std::vector<unsigned char> rgba;  // top row first
  int at(int x, int y, int c) const { return rgba[(size_t(y) * size_t(width) + size_t(x)) * 4 + size_t(c)]; }
};

// An empty Png (width 0) when the file cannot be read as a PNG.
inline Png load_png(const std::string& path) {
  Png png;
  int channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &png.width, &png.height, &channels, 4);
  if (!data) return png;
  png.rgba.assign(data, data + size_t(png.width) * size_t(png.height) * 4);
  stbi_image_free(data);
  return png;
}

}  // namespace oit::test
