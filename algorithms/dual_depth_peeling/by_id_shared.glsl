// Shared by the tie_break=triangle_id shaders of dual depth peeling (see
// by_triangle_id.cpp). Fragments are composited in the reference's order
// (view depth, stable triangle id oit_triangle_id()): the front from the
// smallest key up, the back from the largest down.
//
// Per-pixel state after a pass: the keys (view depth as float bits, stable
// id) of the front and back fragments that pass selected -- the next pass
// composites them -- and the depths next to them: the nearest beyond the
// front one, the farthest before the back one. The fragments not composited
// yet are the keys strictly between the two selected keys; the smallest is
// the smallest id either at the front depth (a tie continues) or, failing
// that, at the front's next depth; the largest likewise, with the largest id.
// Each side's candidates are ranked by one 32-bit value that GL_MIN blending
// can reduce: a band (the selected depth first, then the next depth) plus
// the id (reversed for the back), as the bits of a positive normal float,
// and positive normal floats order like their bits.
#include "algorithms/dual_depth_peeling/bindings.h"

// Candidate bands: [0x00800000, 0x40000000) and [0x40000000, 0x7f800000):
// each holds 0x3f800000 ids (the host checks the scene's ids fit).
#define DUAL_ID_BAND_AT_SELECTED 0x00800000u
#define DUAL_ID_BAND_AT_NEXT 0x40000000u
#define DUAL_ID_MAX_ID 0x3f7fffffu
#define DUAL_ID_NO_CANDIDATE_BITS 0x7f800000u  // +infinity: the identity of GL_MIN
#define DUAL_ID_NO_CANDIDATE uintBitsToFloat(DUAL_ID_NO_CANDIDATE_BITS)

// The smallest front candidate is the smallest key; the smallest back
// candidate the largest key (its id enters reversed).
float dual_id_front_candidate(uint band, uint id) { return uintBitsToFloat(band + id); }
float dual_id_back_candidate(uint band, uint id) { return uintBitsToFloat(band + (DUAL_ID_MAX_ID - id)); }
