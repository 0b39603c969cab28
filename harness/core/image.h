#pragma once
#include <string>
#include <vector>

#include "harness/gl/gl.h"

namespace oit {

// Linear RGBA float image, rows bottom-up as GL returns them.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> rgba;

  float at(int x, int y, int channel) const { return rgba[(size_t(y) * size_t(width) + size_t(x)) * 4 + size_t(channel)]; }
};

Image read_texture_rgba32f(GLuint texture, int width, int height);

// .png: 8-bit RGBA of the linear values (clamped, no sRGB encoding), top row first.
// .pfm: 32-bit float RGB (alpha is not part of the PFM format).
// Throws naming the path when the extension is unknown or writing fails.
void write_image(const Image& image, const std::string& path);
Image read_pfm(const std::string& path);

}  // namespace oit
