#pragma once
// Scalar fields as colour images, for per-pixel error and list-length maps.
// One perceptually uniform colour map (viridis: dark purple = low, yellow =
// high) and one explicit ColourScale per kind of map, so that equal values
// are equal colours in every file and both halves of the viewer's split,
// and a colour bar with numbers says what the colours mean.
#include <string>
#include <vector>

#include "harness/output/image.h"

namespace oit {

// How values map to the colour map's [0, 1]. Values below low take the
// bottom colour, above high the top one.
struct ColourScale {
  enum class Kind { linear, log10 };
  Kind kind = Kind::linear;
  float low = 0.0f, high = 1.0f;  // log10: 0 < low < high
  float position(float value) const;  // in [0, 1]; NaN -> 1
  // Tick values for the colour bar: every decade (log10), or low, middle, high.
  std::vector<float> ticks() const;
  // A tick's number as the colour bars print it ("1e-4", "0.01", "12").
  std::string tick_label(float value) const;
};

// The one scale of every error heatmap (bench --images, the viewer's error
// display, both halves of its A/B split): the largest absolute channel
// difference, log10 from 1e-4 (and anything smaller, exact zero included)
// to 1. A visible 8-bit step (1/255 ~ 4e-3) sits just past the second tick.
ColourScale error_scale();

// viridis at t in [0, 1], sRGB-encoded as the table gives it.
void viridis(float t, float* srgb);

// `values` has one entry per pixel, rows bottom-up like Image; NaN values
// (no value at that pixel) are black; alpha is 1. The RGB are linear (the
// colour map decoded), so write_image's display PNG holds the table colours.
Image heatmap(const std::vector<float>& values, int width, int height, const ColourScale& scale);

// `values` mapped linearly from [low, high] (the field's natural range).
Image heatmap_range(const std::vector<float>& values, int width, int height, float low, float high);

// Per-pixel largest absolute channel difference between two images on
// error_scale().
std::vector<float> error_field(const Image& image, const Image& reference);
Image error_heatmap(const Image& image, const Image& reference);

// `map` with a legend strip below it: the colour bar over `scale` and its
// tick values in digits. The strip depends on the scale alone (not on the
// values), so maps on one scale carry identical bars. The canvas is at
// least kColourBarMinWidth wide (a narrow map gets dark grey beside it).
inline constexpr int kColourBarMinWidth = 200;
inline constexpr int kColourBarHeight = 32;
Image with_colour_bar(const Image& map, const ColourScale& scale);

}  // namespace oit
