#include "harness/output/heatmap.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <stdexcept>

namespace oit {
namespace {

// matplotlib's viridis (Stéfan van der Walt and Nathaniel Smith, 2015, CC0;
// matplotlib/_cm_listed.py `_viridis_data`), entries round(k * 255 / 32)
// of its 256, sRGB: t = k / 32, linear interpolation between them.
constexpr float kViridis[33][3] = {
    {0.267004f, 0.004874f, 0.329415f}, {0.277018f, 0.050344f, 0.375715f}, {0.282327f, 0.094955f, 0.417331f},
    {0.282884f, 0.135920f, 0.453427f}, {0.278826f, 0.175490f, 0.483397f}, {0.270595f, 0.214069f, 0.507052f},
    {0.258965f, 0.251537f, 0.524736f}, {0.244972f, 0.287675f, 0.537260f}, {0.229739f, 0.322361f, 0.545706f},
    {0.214298f, 0.355619f, 0.551184f}, {0.199430f, 0.387607f, 0.554642f}, {0.185556f, 0.418570f, 0.556753f},
    {0.172719f, 0.448791f, 0.557885f}, {0.160665f, 0.478540f, 0.558115f}, {0.149039f, 0.508051f, 0.557250f},
    {0.137770f, 0.537492f, 0.554906f}, {0.127568f, 0.566949f, 0.550556f}, {0.121148f, 0.592739f, 0.544641f},
    {0.120081f, 0.622161f, 0.534946f}, {0.130067f, 0.651384f, 0.521608f}, {0.153894f, 0.680203f, 0.504172f},
    {0.191090f, 0.708366f, 0.482284f}, {0.239374f, 0.735588f, 0.455688f}, {0.296479f, 0.761561f, 0.424223f},
    {0.360741f, 0.785964f, 0.387814f}, {0.430983f, 0.808473f, 0.346476f}, {0.506271f, 0.828786f, 0.300362f},
    {0.585678f, 0.846661f, 0.249897f}, {0.668054f, 0.861999f, 0.196293f}, {0.751884f, 0.874951f, 0.143228f},
    {0.835270f, 0.886029f, 0.102646f}, {0.916242f, 0.896091f, 0.100717f}, {0.993248f, 0.906157f, 0.143936f},
};

void linear_colour(float t, float* rgba) {
  float srgb[3];
  viridis(t, srgb);
  for (int c = 0; c < 3; ++c) rgba[c] = srgb_decode(srgb[c]);
  rgba[3] = 1.0f;
}

// Digits, '.', '-', '+' and 'e' in a 3x5 bitmap font (rows top-down, bit 2
// the left column), enough for the colour bar's numbers.
const unsigned char* glyph(char c) {
  static constexpr unsigned char kDigits[10][5] = {
      {7, 5, 5, 5, 7}, {2, 6, 2, 2, 7}, {7, 1, 7, 4, 7}, {7, 1, 7, 1, 7}, {5, 5, 7, 1, 1},
      {7, 4, 7, 1, 7}, {7, 4, 7, 5, 7}, {7, 1, 1, 1, 1}, {7, 5, 7, 5, 7}, {7, 5, 7, 1, 7}};
  static constexpr unsigned char kDot[5] = {0, 0, 0, 0, 2}, kMinus[5] = {0, 0, 7, 0, 0},
                                 kPlus[5] = {0, 2, 7, 2, 0}, kE[5] = {0, 7, 7, 4, 7};
  if (c >= '0' && c <= '9') return kDigits[c - '0'];
  if (c == '.') return kDot;
  if (c == '-') return kMinus;
  if (c == '+') return kPlus;
  if (c == 'e') return kE;
  throw std::invalid_argument(std::string("colour bar: no glyph for '") + c + "'");
}

// The legend strip, top row first, drawn into `pixels` (width x kColourBarHeight RGBA, linear).
class Strip {
 public:
  explicit Strip(int width) : width_(width), rgba_(size_t(width) * kColourBarHeight * 4) {
    const float grey = srgb_decode(0.15f);
    for (size_t i = 0; i < rgba_.size(); ++i) rgba_[i] = i % 4 == 3 ? 1.0f : grey;
  }
  void set(int x, int y, const float* rgba) {
    if (x >= 0 && x < width_ && y >= 0 && y < kColourBarHeight)
      std::copy_n(rgba, 4, &rgba_[(size_t(y) * size_t(width_) + size_t(x)) * 4]);
  }
  // `text` centred on column x (kept inside the strip), glyphs 2x scaled.
  void text(const std::string& text, int x, int top) {
    constexpr int kScale = 2, kAdvance = 4 * kScale;
    const int width = int(text.size()) * kAdvance - kScale;
    const int left = std::clamp(x - width / 2, 0, std::max(0, width_ - width));
    const float white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    for (size_t i = 0; i < text.size(); ++i) {
      const unsigned char* rows = glyph(text[i]);
      for (int gy = 0; gy < 5 * kScale; ++gy)
        for (int gx = 0; gx < 3 * kScale; ++gx)
          if (rows[gy / kScale] & (4 >> (gx / kScale))) set(left + int(i) * kAdvance + gx, top + gy, white);
    }
  }
  const std::vector<float>& rgba() const { return rgba_; }

 private:
  int width_;
  std::vector<float> rgba_;
};

}  // namespace

float ColourScale::position(float value) const {
  if (std::isnan(value)) return 1.0f;
  if (kind == Kind::log10) {
    if (!(value > low)) return 0.0f;
    return std::clamp((std::log10(value) - std::log10(low)) / (std::log10(high) - std::log10(low)), 0.0f, 1.0f);
  }
  const float span = high > low ? high - low : 1.0f;
  return std::clamp((value - low) / span, 0.0f, 1.0f);
}

std::vector<float> ColourScale::ticks() const {
  if (kind == Kind::linear) return {low, 0.5f * (low + high), high};
  std::vector<float> ticks;
  for (int e = int(std::ceil(std::log10(low) - 1e-4)); e <= int(std::floor(std::log10(high) + 1e-4)); ++e)
    ticks.push_back(std::pow(10.0f, float(e)));
  return ticks;
}

std::string ColourScale::tick_label(float value) const {
  char text[32];
  const int exponent = value > 0.0f ? int(std::lround(std::log10(value))) : 0;
  if (kind == Kind::log10 && exponent <= -3) std::snprintf(text, sizeof text, "1e%d", exponent);
  else std::snprintf(text, sizeof text, "%.3g", double(value));
  return text;
}

ColourScale error_scale() { return {ColourScale::Kind::log10, 1e-4f, 1.0f}; }

void viridis(float t, float* srgb) {
  const float x = std::clamp(std::isfinite(t) ? t : 1.0f, 0.0f, 1.0f) * 32.0f;
  const int k = std::min(int(x), 31);
  const float f = x - float(k);
  for (int c = 0; c < 3; ++c) srgb[c] = kViridis[k][c] + f * (kViridis[k + 1][c] - kViridis[k][c]);
}

Image heatmap(const std::vector<float>& values, int width, int height, const ColourScale& scale) {
  if (values.size() != size_t(width) * size_t(height))
    throw std::invalid_argument("heatmap: " + std::to_string(values.size()) + " values for " + std::to_string(width) +
                                "x" + std::to_string(height) + " pixels");
  Image image{width, height, std::vector<float>(values.size() * 4, 1.0f)};
  for (size_t p = 0; p < values.size(); ++p) {
    if (std::isnan(values[p])) std::fill_n(&image.rgba[4 * p], 3, 0.0f);
    else linear_colour(scale.position(values[p]), &image.rgba[4 * p]);
  }
  return image;
}

Image heatmap_range(const std::vector<float>& values, int width, int height, float low, float high) {
  return heatmap(values, width, height, ColourScale{ColourScale::Kind::linear, low, high});
}

std::vector<float> error_field(const Image& image, const Image& reference) {
  if (image.width != reference.width || image.height != reference.height)
    throw std::invalid_argument("error heatmap: image and reference sizes differ");
  std::vector<float> error(size_t(image.width) * size_t(image.height), 0.0f);
  for (size_t p = 0; p < error.size(); ++p)
    for (size_t c = 0; c < 4; ++c) {
      const float d = std::abs(image.rgba[4 * p + c] - reference.rgba[4 * p + c]);
      error[p] = std::isfinite(d) ? std::max(error[p], d) : 1.0f;  // NaN or inf: the worst colour
    }
  return error;
}

Image error_heatmap(const Image& image, const Image& reference) {
  return heatmap(error_field(image, reference), image.width, image.height, error_scale());
}

Image with_colour_bar(const Image& map, const ColourScale& scale) {
  const int width = std::max(map.width, kColourBarMinWidth);
  Strip strip(width);
  constexpr int kMargin = 12, kBarTop = 4, kBarRows = 10, kTickRows = 3, kLabelTop = 18;
  const int bar = width - 2 * kMargin;
  for (int x = 0; x < bar; ++x) {
    float rgba[4];
    linear_colour((float(x) + 0.5f) / float(bar), rgba);
    for (int y = kBarTop; y < kBarTop + kBarRows; ++y) strip.set(kMargin + x, y, rgba);
  }
  const float white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
  for (float tick : scale.ticks()) {
    const int x = kMargin + std::min(int(std::lround(scale.position(tick) * float(bar))), bar - 1);
    for (int y = kBarTop + kBarRows; y < kBarTop + kBarRows + kTickRows; ++y) strip.set(x, y, white);
    strip.text(scale.tick_label(tick), x, kLabelTop);
  }
  // Rows bottom-up: the strip's bottom row first, then the map above it.
  const float grey = srgb_decode(0.15f);
  Image out{width, map.height + kColourBarHeight, {}};
  out.rgba.reserve(size_t(width) * size_t(out.height) * 4);
  for (int y = kColourBarHeight - 1; y >= 0; --y)
    out.rgba.insert(out.rgba.end(), strip.rgba().begin() + ptrdiff_t(y) * width * 4,
                    strip.rgba().begin() + ptrdiff_t(y + 1) * width * 4);
  for (int y = 0; y < map.height; ++y) {
    out.rgba.insert(out.rgba.end(), map.rgba.begin() + ptrdiff_t(y) * map.width * 4,
                    map.rgba.begin() + ptrdiff_t(y + 1) * map.width * 4);
    for (int x = map.width; x < width; ++x) out.rgba.insert(out.rgba.end(), {grey, grey, grey, 1.0f});
  }
  return out;
}

}  // namespace oit
