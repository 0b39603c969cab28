#include "algorithms/bucketed_kbuffer/transfer_files.h"

#include <stb_image.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace oit::bkb {
namespace {

constexpr size_t kMaxFileBytes = size_t(16) << 20;  // transfer functions are small; refuse anything huge
constexpr int kMaxImageSide = 4096;
// Colours are RGBA8: above 255x every non-zero channel saturates, so larger
// multipliers only risk overflowing the float texture.
constexpr double kMaxMultiplier = 255.0;

// "bucketed_kbuffer: color_transfer_file 'f.txt'": the start of every message.
struct Source {
  std::string label;
  std::string file;
  std::string where() const { return "bucketed_kbuffer: " + label + " '" + file + "'"; }
  std::invalid_argument error(const std::string& what) const { return std::invalid_argument(where() + ": " + what); }
  std::invalid_argument error(int line, const std::string& what) const {
    return std::invalid_argument(where() + ", line " + std::to_string(line) + ": " + what);
  }
};

// A token as it may appear in a message: bounded, printable.
std::string shown(const std::string& token) {
  std::string text;
  for (char c : token.substr(0, 40)) text += (c >= 0x20 && c < 0x7f) ? c : '?';
  return token.size() > 40 ? text + "..." : text;
}

std::string number_text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

struct Row {
  int line = 0;
  std::vector<double> values;
};

// The numbers of every line that has any ('#' comments, blank lines skipped),
// separated by whitespace or commas.
std::vector<Row> numeric_rows(const std::string& text, const Source& source) {
  std::vector<Row> rows;
  int line = 0;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    ++line;
    std::string content = text.substr(start, end - start);
    start = end + 1;
    content = content.substr(0, content.find('#'));
    Row row{line, {}};
    size_t i = 0;
    auto separator = [](char c) { return c == ' ' || c == '\t' || c == ',' || c == '\r' || c == '\v' || c == '\f'; };
    while (i < content.size()) {
      while (i < content.size() && separator(content[i])) ++i;
      size_t j = i;
      while (j < content.size() && !separator(content[j])) ++j;
      if (j == i) break;
      const std::string token = content.substr(i, j - i);
      i = j;
      const char* first = token.data() + (token[0] == '+' ? 1 : 0);
      const char* last = token.data() + token.size();
      double value = 0.0;
      const auto [end_of_number, ec] = std::from_chars(first, last, value);
      if (ec != std::errc() || end_of_number != last || first == last)
        throw source.error(line, "'" + shown(token) + "' is not a number");
      if (!std::isfinite(value)) throw source.error(line, "'" + shown(token) + "' is not a finite number");
      row.values.push_back(value);
    }
    if (!row.values.empty()) rows.push_back(std::move(row));
  }
  if (rows.empty()) throw source.error("has no values (empty, or only blank lines and comments)");
  return rows;
}

// Texel i of `size` evenly spaced over [0, 1] between the samples j and j + 1
// of `n` evenly spaced ones: s = i (n - 1) / (size - 1), exact when n == size.
void sample_position(int i, int size, size_t n, size_t& j, double& t) {
  if (n == 1) {
    j = 0;
    t = 0.0;
    return;
  }
  const double s = double(i) * double(n - 1) / double(size - 1);
  j = std::min(size_t(s), n - 2);
  t = s - double(j);
}

using Rgb = std::array<double, 3>;

// Evenly spaced samples over kappa in [-1, 1] -> RGBA texels.
std::vector<float> color_texels_from_samples(const std::vector<Rgb>& samples) {
  std::vector<float> texels;
  texels.reserve(size_t(kColorTransferSize) * 4);
  for (int i = 0; i < kColorTransferSize; ++i) {
    size_t j = 0;
    double t = 0.0;
    sample_position(i, kColorTransferSize, samples.size(), j, t);
    for (int c = 0; c < 3; ++c)
      texels.push_back(float(t == 0.0 ? samples[j][c] : (1.0 - t) * samples[j][c] + t * samples[j + 1][c]));
    texels.push_back(1.0f);
  }
  return texels;
}

// Samples at strictly increasing kappas -> RGBA texels (piecewise linear,
// constant beyond the ends).
std::vector<float> color_texels_from_keys(const std::vector<double>& kappas, const std::vector<Rgb>& samples) {
  std::vector<float> texels;
  texels.reserve(size_t(kColorTransferSize) * 4);
  size_t j = 0;
  for (int i = 0; i < kColorTransferSize; ++i) {
    const double kappa = -1.0 + 2.0 * double(i) / double(kColorTransferSize - 1);
    while (j + 1 < kappas.size() && kappas[j + 1] <= kappa) ++j;
    Rgb value = samples[j];
    if (kappa > kappas[j] && j + 1 < kappas.size()) {
      const double t = (kappa - kappas[j]) / (kappas[j + 1] - kappas[j]);
      for (int c = 0; c < 3; ++c) value[c] = (1.0 - t) * samples[j][c] + t * samples[j + 1][c];
    }
    for (double v : value) texels.push_back(float(v));
    texels.push_back(1.0f);
  }
  return texels;
}

// A rows x cols grid (row-major, row = depth, column = |kappa|) -> the
// kOpacityTransferSize^2 texels, bilinear.
std::vector<float> opacity_texels_from_grid(const std::vector<double>& grid, size_t rows, size_t cols) {
  std::vector<float> texels;
  texels.reserve(size_t(kOpacityTransferSize) * kOpacityTransferSize);
  for (int y = 0; y < kOpacityTransferSize; ++y) {
    size_t r = 0;
    double ty = 0.0;
    sample_position(y, kOpacityTransferSize, rows, r, ty);
    const size_t r1 = std::min(r + 1, rows - 1);
    for (int x = 0; x < kOpacityTransferSize; ++x) {
      size_t c = 0;
      double tx = 0.0;
      sample_position(x, kOpacityTransferSize, cols, c, tx);
      const size_t c1 = std::min(c + 1, cols - 1);
      auto at = [&](size_t row, size_t col) { return grid[row * cols + col]; };
      const double top = tx == 0.0 ? at(r, c) : (1.0 - tx) * at(r, c) + tx * at(r, c1);
      const double bottom = tx == 0.0 ? at(r1, c) : (1.0 - tx) * at(r1, c) + tx * at(r1, c1);
      texels.push_back(float(ty == 0.0 ? top : (1.0 - ty) * top + ty * bottom));
    }
  }
  return texels;
}

// Throws unless `row` holds the `columns` values of the first row, named
// `first_row` in the message; `rule` says why every row must.
void check_row_width(const Source& source, const Row& row, size_t columns, const std::string& first_row,
                     const std::string& rule) {
  if (row.values.size() != columns)
    throw source.error(row.line, std::to_string(row.values.size()) + " values, but " + first_row + " has " +
                                     std::to_string(columns) + ": " + rule);
}

// `value`, the `what` of `row`; throws naming it when it is outside [low, high].
double in_range(const Source& source, const Row& row, const std::string& what, double value, double low,
                double high) {
  if (value < low || value > high)
    throw source.error(row.line, what + " " + number_text(value) + " is outside [" + number_text(low) + ", " +
                                     number_text(high) + "]");
  return value;
}

std::vector<float> parse_color(const std::string& text, const Source& source) {
  const std::vector<Row> rows = numeric_rows(text, source);
  const size_t columns = rows.front().values.size();
  if (columns > 4)
    throw source.error(rows.front().line, std::to_string(columns) +
                                              " values; a line is 'm', 'r g b', 'kappa m' or 'kappa r g b'");
  const bool keyed = columns == 2 || columns == 4;
  std::vector<double> kappas;
  std::vector<Rgb> samples;
  for (const Row& row : rows) {
    check_row_width(source, row, columns, "line " + std::to_string(rows.front().line),
                    "every line must have the same form");
    if (keyed) {
      const double kappa = in_range(source, row, "kappa", row.values[0], -1.0, 1.0);
      if (!kappas.empty() && kappa <= kappas.back())
        throw source.error(row.line, "kappa " + number_text(kappa) + " does not increase (previous " +
                                         number_text(kappas.back()) + ")");
      kappas.push_back(kappa);
    }
    Rgb rgb{};
    for (int c = 0; c < 3; ++c) {
      rgb[c] = in_range(source, row, "multiplier", row.values[std::min(size_t(keyed) + size_t(c), columns - 1)],
                        0.0, kMaxMultiplier);
    }
    samples.push_back(rgb);
  }
  return keyed ? color_texels_from_keys(kappas, samples) : color_texels_from_samples(samples);
}

std::vector<float> parse_opacity(const std::string& text, const Source& source) {
  const std::vector<Row> rows = numeric_rows(text, source);
  const size_t columns = rows.front().values.size();
  std::vector<double> grid;
  for (const Row& row : rows) {
    check_row_width(source, row, columns, "the first row (line " + std::to_string(rows.front().line) + ")",
                    "the grid must be rectangular");
    for (size_t c = 0; c < columns; ++c)
      grid.push_back(in_range(source, row, "column " + std::to_string(c + 1) + ": opacity", row.values[c], 0.0, 1.0));
  }
  return opacity_texels_from_grid(grid, rows.size(), columns);
}

std::string read_file(const Source& source) {
  std::ifstream in(source.file, std::ios::binary);
  if (!in) throw source.error("cannot be opened for reading");
  std::string bytes;
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    bytes.append(buffer, size_t(in.gcount()));
    if (bytes.size() > kMaxFileBytes)
      throw source.error("is larger than " + std::to_string(kMaxFileBytes >> 20) + " MiB");
  }
  if (in.bad()) throw source.error("could not be read");
  return bytes;
}

bool is_png(const std::string& bytes) { return bytes.rfind("\x89PNG\r\n\x1a\n", 0) == 0; }

struct DecodedImage {
  int width = 0, height = 0, channels = 0;
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels{nullptr, stbi_image_free};
  double at(int x, int y, int c) const {
    return double(pixels.get()[(size_t(y) * size_t(width) + size_t(x)) * size_t(channels) + size_t(c)]) / 255.0;
  }
};

// 8 bits per channel (stb_image reduces 16-bit PNGs), `channels` = 3 (rgb)
// or 1 (grey; stb reduces colour to luma).
DecodedImage decode_png(const std::string& bytes, int channels, const Source& source) {
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int length = int(bytes.size());
  DecodedImage image;
  int components = 0;
  if (!stbi_info_from_memory(data, length, &image.width, &image.height, &components))
    throw source.error(std::string("is not a readable PNG (stb_image: ") + stbi_failure_reason() + ")");
  if (image.width < 1 || image.height < 1 || image.width > kMaxImageSide || image.height > kMaxImageSide)
    throw source.error("is a " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                       " PNG; transfer function images are 1.." + std::to_string(kMaxImageSide) + " pixels a side");
  image.pixels.reset(stbi_load_from_memory(data, length, &image.width, &image.height, &components, channels));
  if (!image.pixels)
    throw source.error(std::string("is not a readable PNG (stb_image: ") + stbi_failure_reason() + ")");
  image.channels = channels;
  return image;
}

std::vector<float> color_from_png(const std::string& bytes, const Source& source) {
  const DecodedImage image = decode_png(bytes, 3, source);
  std::vector<Rgb> samples(size_t(image.width));
  for (int x = 0; x < image.width; ++x)
    for (int c = 0; c < 3; ++c) samples[size_t(x)][size_t(c)] = image.at(x, 0, c);
  return color_texels_from_samples(samples);
}

std::vector<float> opacity_from_png(const std::string& bytes, const Source& source) {
  const DecodedImage image = decode_png(bytes, 1, source);
  std::vector<double> grid;
  grid.reserve(size_t(image.width) * size_t(image.height));
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) grid.push_back(image.at(x, y, 0));
  return opacity_texels_from_grid(grid, size_t(image.height), size_t(image.width));
}

const char* const kColorLabel = "color_transfer_file";
const char* const kOpacityLabel = "opacity_transfer_file";

}  // namespace

std::vector<float> parse_color_transfer_text(const std::string& text, const std::string& file) {
  return parse_color(text, Source{kColorLabel, file});
}

std::vector<float> parse_opacity_transfer_text(const std::string& text, const std::string& file) {
  return parse_opacity(text, Source{kOpacityLabel, file});
}

std::vector<float> load_color_transfer_file(const std::string& path) {
  const Source source{kColorLabel, path};
  const std::string bytes = read_file(source);
  return is_png(bytes) ? color_from_png(bytes, source) : parse_color(bytes, source);
}

std::vector<float> load_opacity_transfer_file(const std::string& path) {
  const Source source{kOpacityLabel, path};
  const std::string bytes = read_file(source);
  return is_png(bytes) ? opacity_from_png(bytes, source) : parse_opacity(bytes, source);
}

}  // namespace oit::bkb
