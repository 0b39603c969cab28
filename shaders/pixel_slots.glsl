// The parameters of a technique that keeps k entries per pixel
// (shaders/pixel_slots.h): `slots.k` and the pixel's index.
#include "shaders/pixel_storage.glsl"
#include "shaders/pixel_slots.h"

layout(std140, binding = OIT_PIXEL_SLOTS_PARAMS_BLOCK) uniform PixelSlotsBlock { PixelSlotsParams slots; };

uint slots_pixel() { return oit_pixel_index(slots.width); }
