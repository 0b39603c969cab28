// kbuffer's binding points and uniform locations, included by its C++ and
// its GLSL alike so that no number is copied by hand between the two
// (shaders/bindings.h: a technique's own start at OIT_FIRST_TECHNIQUE_*).
#ifndef OIT_KBUFFER_BINDINGS_H
#define OIT_KBUFFER_BINDINGS_H

#include "shaders/bindings.h"

// Storage buffer binding points.
#define KBUFFER_KEYS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define KBUFFER_OWNERS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 1)
#define KBUFFER_COLORS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 2)
#define KBUFFER_COUNTERS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 3)

// Texture units.
#define KBUFFER_TAIL_ACCUMULATION_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define KBUFFER_TAIL_REVEALAGE_UNIT (OIT_FIRST_TECHNIQUE_BINDING + 1)

// Uniform buffer binding of the frame's parameters (KBufferFrameParams).
#define KBUFFER_FRAME_PARAMS_BLOCK 0

// The frame's parameters, one std140 uniform block uploaded once per frame
// (kbuffer_storage.glsl reads it as `kbuffer`). Every member is a 4-byte
// scalar, so std140 packs them as C++ does (static_assert in kbuffer.cpp).
#ifdef __cplusplus
namespace oit::kbuffer {
#endif
struct KBufferFrameParams {
  int width;  // the frame's pixels per row
  // Slots per pixel, 1 <= k <= K. Not the define K: with k=auto one program
  // (K = the next power of two) serves every k up to K, and loops bounded by
  // a uniform are not unrolled, which made compose faster on llvmpipe
  // (README, "k=auto"). K only sizes compose's local arrays.
  int k;
  int unused_0, unused_1;  // the block padded to 16 bytes
};
#ifdef __cplusplus
}  // namespace oit::kbuffer
#endif

#endif
