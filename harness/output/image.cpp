#include "harness/output/image.h"

#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "harness/output/output_file.h"

namespace oit {

Image read_texture_rgba32f(GLuint texture, int width, int height) {
  Image image{width, height, std::vector<float>(size_t(width) * size_t(height) * 4)};
  glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(image.rgba.size() * sizeof(float)), image.rgba.data());
  return image;
}

float srgb_encode(float linear) {
  const float v = std::isfinite(linear) ? std::clamp(linear, 0.0f, 1.0f) : 0.0f;
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

float srgb_decode(float encoded) {
  const float v = std::clamp(encoded, 0.0f, 1.0f);
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

PngEncoding parse_png_encoding(const std::string& text) {
  if (text == "display") return PngEncoding::display;
  if (text == "linear") return PngEncoding::raw;
  throw std::invalid_argument("--png '" + text + "': expected display or linear");
}

namespace {

void append_bytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

uint8_t to_byte(float v) { return uint8_t(std::lround((std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f) * 255.0f)); }

std::string png_bytes(const Image& image, const std::string& path, PngEncoding encoding) {
  std::vector<uint8_t> bytes(image.rgba.size());
  for (int y = 0; y < image.height; ++y) {
    const int source_row = image.height - 1 - y;  // PNG is top row first
    for (int x = 0; x < image.width * 4; ++x) {
      const float v = image.rgba[size_t(source_row) * size_t(image.width) * 4 + size_t(x)];
      const bool alpha = x % 4 == 3;
      bytes[size_t(y) * size_t(image.width) * 4 + size_t(x)] = encoding == PngEncoding::raw ? to_byte(v)
                                                               : alpha                     ? uint8_t(255)
                                                                                           : to_byte(srgb_encode(v));
    }
  }
  std::string encoded;
  if (!stbi_write_png_to_func(append_bytes, &encoded, image.width, image.height, 4, bytes.data(), image.width * 4))
    throw std::runtime_error("cannot encode PNG '" + path + "' (" + std::to_string(image.width) + "x" +
                             std::to_string(image.height) + ")");
  return encoded;
}

std::string pfm_bytes(const Image& image) {
  // Negative scale = little endian; PFM rows are bottom-up, as GL's are.
  std::string bytes = "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
  const size_t header = bytes.size();
  bytes.resize(header + size_t(image.width) * size_t(image.height) * 3 * sizeof(float));
  char* out = bytes.data() + header;
  for (size_t i = 0; i < image.rgba.size(); i += 4, out += 3 * sizeof(float))
    std::memcpy(out, &image.rgba[i], 3 * sizeof(float));
  return bytes;
}

std::string encoded_file(const Image& image, const std::string& path, PngEncoding encoding) {
  const std::string extension = std::filesystem::path(path).extension().string();
  if (extension == ".png") return png_bytes(image, path, encoding);
  if (extension == ".pfm") return pfm_bytes(image);
  throw std::invalid_argument("output '" + path + "' must end in .png or .pfm");
}

}  // namespace

void write_image(const Image& image, const std::string& path, PngEncoding encoding) {
  write_file_atomically(path, encoded_file(image, path, encoding));
}

std::string write_new_image(const Image& image, const std::string& path, PngEncoding encoding) {
  const std::string bytes = encoded_file(image, path, encoding);
  const std::filesystem::path p(path);
  const std::string stem = (p.parent_path() / p.stem()).string(), extension = p.extension().string();
  for (int n = 1; n < 100000; ++n) {
    const std::string candidate = n == 1 ? path : stem + "_" + std::to_string(n) + extension;
    if (std::filesystem::exists(std::filesystem::symlink_status(candidate))) continue;  // quick skip; link(2) decides
    if (write_new_file_atomically(candidate, bytes)) return candidate;
  }
  throw std::runtime_error("cannot find a free name for '" + path + "' (" + stem + "_2 .. _99999 exist)");
}

Image read_pfm(const std::string& path) {
  require_regular_file(path, "PFM image");
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
