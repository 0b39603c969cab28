// bucketed_kbuffer's binding points, texture units and uniform locations,
// included by its C++ and its GLSL alike so that no number is copied by hand
// between the two (shaders/bindings.h: a technique's own start at
// OIT_FIRST_TECHNIQUE_*).
#ifndef OIT_BUCKETED_KBUFFER_BINDINGS_H
#define OIT_BUCKETED_KBUFFER_BINDINGS_H

#include "shaders/bindings.h"

// Storage buffer binding points (bkb_common.glsl), consecutive: the C++ binds
// its ten buffers in this order from BKB_Z_BINDING.
#define BKB_Z_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define BKB_BUCKETS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 1)
#define BKB_COLORS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 2)
#define BKB_NORMALS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 3)
#define BKB_FEATURES_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 4)
#define BKB_COUNTERS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 5)
#define BKB_LINKS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 6)
#define BKB_EXPECTED_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 7)
#define BKB_ESTIMATED_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 8)
#define BKB_TRUTH_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 9)
#define BKB_BUFFER_COUNT 10

// Texture units of the stylize pass.
#define BKB_COLOR_TRANSFER_UNIT 0
#define BKB_OPACITY_TRANSFER_UNIT 1

// Uniform buffer binding of the frame's parameters (BkbFrameParams).
#define BKB_FRAME_PARAMS_BLOCK 0

// The frame's parameters, one std140 uniform block uploaded once per frame
// (bkb_common.glsl reads it as `bkb`). A mat4 first, then 4-byte scalars:
// std140 packs them as C++ does (static_assert in bucketed_kbuffer.cpp).
#ifdef __cplusplus
#include <glm/mat4x4.hpp>
namespace oit::bkb {
using mat4 = glm::mat4;
#endif
struct BkbFrameParams {
  mat4 inverse_projection;       // pixel rays (neighbors.frag)
  int width, height;             // the frame's pixels
  float depth_near, depth_far;   // view-depth range mapped onto [0, BKB_DEPTH_MAX]
  float curvature_scale;         // kappa = tanh(curvature_scale * (k1 + k2)) (neighbors.frag)
  int unused_0, unused_1, unused_2;  // the block padded to a multiple of 16 bytes
};
#ifdef __cplusplus
}  // namespace oit::bkb
#endif

#endif
