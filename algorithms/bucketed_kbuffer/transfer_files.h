#pragma once
// User transfer functions for the stylize pass (murray2016 section 5.2),
// read from the files named by the parameters color_transfer_file and
// opacity_transfer_file, and resampled (linear interpolation) to the texel
// grids of transfer_functions.h. No GL here: the fuzz target links this file
// alone. Formats (README.md, "Transfer functions from files"):
//   colour, text:  one entry per line, the same form on every line:
//                  "m" or "r g b" (evenly spaced over kappa -1 .. 1), or
//                  "kappa m" / "kappa r g b" (kappa strictly increasing in
//                  [-1, 1], held constant beyond the first and last);
//                  multipliers in [0, 255].
//   colour, PNG:   the first row, left = kappa -1, right = +1; rgb / 255.
//   opacity, text: a rectangular grid in [0, 1]; rows = depth (first row
//                  = depth 0, the nearest), columns = |kappa| (first = 0).
//   opacity, PNG:  the same orientation (top row = depth 0, left column =
//                  |kappa| 0); grey / 255 (colour images reduced to luma).
// Text: '#' starts a comment, numbers are separated by spaces, tabs or
// commas. A file is a PNG when it starts with the PNG signature.
// Every error is a std::invalid_argument naming the file and the line
// (text) and the offending value, or stb_image's reason (PNG).
#include <string>
#include <vector>

namespace oit::bkb {

// The texel grids the stylize pass samples, shared with the built-ins.
constexpr int kColorTransferSize = 256;   // texels of the 1D colour function over kappa in [-1, 1]
constexpr int kOpacityTransferSize = 64;  // texels per axis of the 2D opacity function

// kColorTransferSize RGBA texels (a = 1), as color_texels() of transfer_functions.h.
std::vector<float> parse_color_transfer_text(const std::string& text, const std::string& file);
// kOpacityTransferSize^2 texels, row-major with y = depth, as opacity_texels().
std::vector<float> parse_opacity_transfer_text(const std::string& text, const std::string& file);

// Reads the file (text or PNG) and parses it as above.
std::vector<float> load_color_transfer_file(const std::string& path);
std::vector<float> load_opacity_transfer_file(const std::string& path);

}  // namespace oit::bkb
