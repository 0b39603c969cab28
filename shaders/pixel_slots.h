// The parameters of a technique that keeps k entries per pixel, pixel-major
// (entry i of pixel p at p * k + i, oit_pixel_index): adaptive_transparency's
// nodes, multi_layer_alpha_blending's layers, hybrid_transparency's core
// slots, kbuffer's slots. One std140 struct for their C++ (UniformBlock<PixelSlotsParams> at
// OIT_PIXEL_SLOTS_PARAMS_BLOCK) and their GLSL (shaders/pixel_slots.glsl).
#ifndef OIT_SHADERS_PIXEL_SLOTS_H
#define OIT_SHADERS_PIXEL_SLOTS_H

#include "shaders/std140.h"

#define OIT_PIXEL_SLOTS_PARAMS_BLOCK 0

OIT_STD140_BEGIN
struct PixelSlotsParams {
  int width;  // the frame's width in pixels
  int k;      // entries per pixel
  int unused_0, unused_1;
};
OIT_STD140_END

#endif
