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

// The sRGB transfer function (IEC 61966-2-1) on one channel in [0, 1].
float srgb_encode(float linear);
float srgb_decode(float encoded);

// How a PNG holds the image's values.
//  display: what a screen should show. RGB sRGB-encoded, alpha 255. Every
//    technique's RGB is already composited over the run's background
//    (shaders/compose.glsl: accumulated + transmittance * background), so
//    leaving out alpha (the coverage) is the composite; keeping it made
//    viewers blend a second time over their own backdrop (pale models).
//  raw: the values as they are, alpha kept (window screenshots, whose
//    values are display bytes already).
enum class PngEncoding { display, raw };
// The --png option: "display" or "linear" (raw: the linear values, alpha =
// coverage, as PNGs were before); throws naming the text otherwise.
PngEncoding parse_png_encoding(const std::string& text);

// .png: 8-bit, top row first, `encoding` above (values clamped to [0, 1]).
// .pfm: 32-bit float linear RGB (alpha is not part of the PFM format).
// Throws naming the path when the extension is unknown or writing fails.
void write_image(const Image& image, const std::string& path, PngEncoding encoding = PngEncoding::display);
// write_image to a name no file has yet: `path`, else STEM_2.EXT,
// STEM_3.EXT, ...; returns the path written. Never replaces a file, even
// one another process writes at the same moment.
std::string write_new_image(const Image& image, const std::string& path,
                            PngEncoding encoding = PngEncoding::display);
Image read_pfm(const std::string& path);

}  // namespace oit
