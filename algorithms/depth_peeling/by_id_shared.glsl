// Shared by the tie_break=triangle_id shaders of depth peeling (see
// by_triangle_id.cpp). Fragments are peeled in the reference's order
// (view depth, stable triangle id oit_triangle_id()).
//
// Per-pixel state after a pass, one RGBA32UI texel (one fetch): the key
// (view depth as float bits, stable id) of the fragment that pass selected
// -- the next pass composites it -- and `next`, the nearest view depth beyond
// the selected depth, as float bits. Before anything is selected the key is
// (-infinity, 0) and `next` -infinity: "the nearest depth is not known yet". Among the
// fragments not composited yet, the next in order is the one with the
// smallest id either at the selected depth (a tie continues) or, failing
// that, at `next`. Both candidates are ranked by one 32-bit value, a band
// (selected depth first, then next depth) plus the id, which GL_MIN
// blending can reduce: the band and id as the bits of a positive normal
// float, and positive normal floats order like their bits.
#include "algorithms/depth_peeling/bindings.h"

// Candidate bands: [0x00800000, 0x40000000) and [0x40000000, 0x7f800000):
// each holds 0x3f800000 ids (the host checks the scene's ids fit).
#define DP_ID_BAND_AT_SELECTED 0x00800000u
#define DP_ID_BAND_AT_NEXT 0x40000000u
#define DP_ID_NO_CANDIDATE_BITS 0x7f800000u  // +infinity: the identity of GL_MIN
#define DP_ID_NO_CANDIDATE uintBitsToFloat(DP_ID_NO_CANDIDATE_BITS)
#define DP_ID_NEAREST_NOT_KNOWN_BITS 0xff800000u  // -infinity as `next`: before pass 1

float dp_id_candidate(uint band, uint id) { return uintBitsToFloat(band + id); }
