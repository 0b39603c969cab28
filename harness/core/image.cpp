#include "core/image.h"

#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace oit {

Image read_texture_rgba32f(GLuint texture, int width, int height) {
  Image image{width, height, std::vector<float>(size_t(width) * size_t(height) * 4)};
  glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(image.rgba.size() * sizeof(float)), image.rgba.data());
  return image;
}

namespace {

void write_png(const Image& image, const std::string& path) {
  std::vector<uint8_t> bytes(image.rgba.size());
  for (int y = 0; y < image.height; ++y) {
    const int source_row = image.height - 1 - y;  // PNG is top row first
    for (int x = 0; x < image.width * 4; ++x) {
      const float v = image.rgba[size_t(source_row) * size_t(image.width) * 4 + size_t(x)];
      const float clamped = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
      bytes[size_t(y) * size_t(image.width) * 4 + size_t(x)] = uint8_t(std::lround(clamped * 255.0f));
    }
  }
  if (!stbi_write_png(path.c_str(), image.width, image.height, 4, bytes.data(), image.width * 4)) {
    throw std::runtime_error("cannot write PNG '" + path + "'");
  }
}

void write_pfm(const Image& image, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot open '" + path + "' for writing");
  // Negative scale = little endian; PFM rows are bottom-up, as GL's are.
  out << "PF\n" << image.width << " " << image.height << "\n-1.0\n";
  std::vector<float> rgb;
  rgb.reserve(size_t(image.width) * size_t(image.height) * 3);
  for (size_t i = 0; i < image.rgba.size(); i += 4) rgb.insert(rgb.end(), &image.rgba[i], &image.rgba[i] + 3);
  out.write(reinterpret_cast<const char*>(rgb.data()), std::streamsize(rgb.size() * sizeof(float)));
  if (!out) throw std::runtime_error("failed writing '" + path + "'");
}

}  // namespace

void write_image(const Image& image, const std::string& path) {
  const std::string extension = std::filesystem::path(path).extension().string();
  if (const auto parent = std::filesystem::path(path).parent_path(); !parent.empty()) {
    std::filesystem::create_directories(parent);
  }
  if (extension == ".png") return write_png(image, path);
  if (extension == ".pfm") return write_pfm(image, path);
  throw std::invalid_argument("output '" + path + "' must end in .png or .pfm");
}

Image read_pfm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open '" + path + "'");
  std::string magic;
  double scale = 0.0;
  Image image;
  in >> magic >> image.width >> image.height >> scale;
  in.get();
  if (magic != "PF" || image.width <= 0 || image.height <= 0 || scale >= 0.0 || image.width > 65536 ||
      image.height > 65536) {
    throw std::runtime_error("'" + path + "' is not a little-endian RGB PFM file");
  }
  const size_t pixels = size_t(image.width) * size_t(image.height);
  std::vector<float> rgb(pixels * 3);
  in.read(reinterpret_cast<char*>(rgb.data()), std::streamsize(rgb.size() * sizeof(float)));
  if (!in) throw std::runtime_error("'" + path + "' is truncated");
  image.rgba.resize(pixels * 4, 1.0f);
  for (size_t i = 0; i < pixels; ++i) std::memcpy(&image.rgba[i * 4], &rgb[i * 3], 3 * sizeof(float));
  return image;
}

}  // namespace oit
