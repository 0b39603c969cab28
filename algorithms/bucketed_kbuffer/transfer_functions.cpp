#include "algorithms/bucketed_kbuffer/transfer_functions.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace oit::bkb {
namespace {

float smoothstep(float edge0, float edge1, float x) {
  const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

void use_linear_clamped_filtering(GLuint texture) {
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

}  // namespace

float color_multiplier(ColorTransfer function, float kappa) {
  kappa = std::clamp(kappa, -1.0f, 1.0f);
  switch (function) {
    case ColorTransfer::identity: return 1.0f;
    // 1.5x on the strongest convexity, 0.5x on the strongest concavity, flat unchanged.
    case ColorTransfer::mean_curvature_shading: return 1.0f - 0.5f * kappa;
    // Flat at half brightness, either sign of curvature up to 1.5x.
    case ColorTransfer::curved_bright: return 0.5f + std::abs(kappa);
  }
  return 1.0f;
}

float opacity(OpacityTransfer function, float abs_kappa, float depth) {
  abs_kappa = std::clamp(abs_kappa, 0.0f, 1.0f);
  depth = std::clamp(depth, 0.0f, 1.0f);
  switch (function) {
    case OpacityTransfer::identity: break;
    case OpacityTransfer::front_focus: {
      // 0.05 on flat surfaces at the front, 0.95 on curved ones; the flat
      // opacity grows quickly with depth, saturating at 0.59 at the back.
      const float curved = smoothstep(0.05f, 0.6f, abs_kappa);
      const float far = 1.0f - std::pow(1.0f - depth, 3.0f);
      return 0.05f + 0.9f * (1.0f - (1.0f - curved) * (1.0f - 0.6f * far));
    }
    case OpacityTransfer::depth_range: {
      // Curvature decides at every depth (a wider kappa ramp), depth adds
      // only a mild linear term: the front is not emphasised.
      const float curved = smoothstep(0.02f, 0.9f, abs_kappa);
      return 0.1f + 0.7f * curved + 0.15f * depth;
    }
  }
  throw std::logic_error("bucketed_kbuffer: the identity opacity keeps each fragment's alpha");
}

std::vector<float> color_texels(ColorTransfer function) {
  std::vector<float> texels;
  texels.reserve(size_t(kColorTransferSize) * 4);
  for (int i = 0; i < kColorTransferSize; ++i) {
    const float m = color_multiplier(function, -1.0f + 2.0f * float(i) / float(kColorTransferSize - 1));
    texels.insert(texels.end(), {m, m, m, 1.0f});
  }
  return texels;
}

std::vector<float> opacity_texels(OpacityTransfer function) {
  std::vector<float> texels;
  texels.reserve(size_t(kOpacityTransferSize) * kOpacityTransferSize);
  const float last = float(kOpacityTransferSize - 1);
  for (int y = 0; y < kOpacityTransferSize; ++y)
    for (int x = 0; x < kOpacityTransferSize; ++x)
      texels.push_back(opacity(function, float(x) / last, float(y) / last));
  return texels;
}

std::vector<float> color_transfer_texels(ColorTransfer choice, const std::string& file) {
  if (!file.empty()) return load_color_transfer_file(file);
  return choice == ColorTransfer::identity ? std::vector<float>{} : color_texels(choice);
}

std::vector<float> opacity_transfer_texels(OpacityTransfer choice, const std::string& file) {
  if (!file.empty()) return load_opacity_transfer_file(file);
  return choice == OpacityTransfer::identity ? std::vector<float>{} : opacity_texels(choice);
}

Texture make_color_texture(const std::vector<float>& texels) {
  if (texels.size() != size_t(kColorTransferSize) * 4)
    throw std::logic_error("bucketed_kbuffer: colour transfer texels of the wrong size");
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_1D, 1, &id);
  Texture texture(id);
  glTextureStorage1D(id, 1, GL_RGBA32F, kColorTransferSize);
  glTextureSubImage1D(id, 0, 0, kColorTransferSize, GL_RGBA, GL_FLOAT, texels.data());
  use_linear_clamped_filtering(id);
  return texture;
}

Texture make_opacity_texture(const std::vector<float>& texels) {
  if (texels.size() != size_t(kOpacityTransferSize) * kOpacityTransferSize)
    throw std::logic_error("bucketed_kbuffer: opacity transfer texels of the wrong size");
  Texture texture = make_texture_2d(GL_R32F, kOpacityTransferSize, kOpacityTransferSize);
  glTextureSubImage2D(texture.id(), 0, 0, 0, kOpacityTransferSize, kOpacityTransferSize, GL_RED, GL_FLOAT,
                      texels.data());
  use_linear_clamped_filtering(texture.id());
  return texture;
}

}  // namespace oit::bkb
