#pragma once
// The stylization transfer functions of the bucketed k-buffer (murray2016
// section 5.2), as plain functions (tests evaluate them too) and as the
// texture contents the stylize pass samples. The shapes follow the paper's
// example figures; the figures give no formulas, so the curves here are
// smooth functions with the behaviour the text describes.
#include <string>
#include <vector>

#include "base/params.h"
#include "harness/gl/handles.h"
#include "algorithms/bucketed_kbuffer/transfer_files.h"  // kColorTransferSize, kOpacityTransferSize

namespace oit::bkb {

enum class ColorTransfer {
  identity,                // the shaded colour unchanged
  mean_curvature_shading,  // Figure 6(a): bright convexities (kappa -> -1), dark concavities (+1)
  curved_bright,           // Figure 6(b): bright curved surfaces, dark flat ones
};
enum class OpacityTransfer {
  identity,     // the fragment's own alpha unchanged
  front_focus,  // Figures 7/8(a): transparent flat and near, opaque curved, opacity quickly growing with depth
  depth_range,  // Figures 7/8(b): less focus in front, curvature shown over a wider range of depth
};

// The color_transfer and opacity_transfer parameters' choices.
inline const Choices<ColorTransfer> kColorTransfers{{ColorTransfer::mean_curvature_shading, "mean_curvature_shading"},
                                                   {ColorTransfer::curved_bright, "curved_bright"},
                                                   {ColorTransfer::identity, "identity"}};
inline const Choices<OpacityTransfer> kOpacityTransfers{{OpacityTransfer::front_focus, "front_focus"},
                                                        {OpacityTransfer::depth_range, "depth_range"},
                                                        {OpacityTransfer::identity, "identity"}};

// Multiplier of the shaded rgb (the same for r, g, b); kappa in [-1, 1].
float color_multiplier(ColorTransfer function, float kappa);
// The opacity replacing the fragment's alpha; abs_kappa and depth in [0, 1].
// Not defined for OpacityTransfer::identity (the stylize pass keeps alpha).
float opacity(OpacityTransfer function, float abs_kappa, float depth);

// Texture contents: kColorTransferSize RGBA texels (m, m, m, 1) from
// kappa = -1 to +1, and kOpacityTransferSize^2 R texels (x: |kappa|, y: depth).
std::vector<float> color_texels(ColorTransfer function);
std::vector<float> opacity_texels(OpacityTransfer function);

// The texels for the parameters: those of the file when one is named (it
// overrides the choice; transfer_files.h), else of the built-in the choice
// names; empty for the identity choice without a file (no texture: the
// stylize pass leaves that part alone).
std::vector<float> color_transfer_texels(ColorTransfer choice, const std::string& file);
std::vector<float> opacity_transfer_texels(OpacityTransfer choice, const std::string& file);

// The textures the stylize pass samples (linear filtering, clamped), from
// texels laid out as color_texels() / opacity_texels().
Texture make_color_texture(const std::vector<float>& texels);    // GL_TEXTURE_1D, RGBA32F
Texture make_opacity_texture(const std::vector<float>& texels);  // GL_TEXTURE_2D, R32F

}  // namespace oit::bkb
