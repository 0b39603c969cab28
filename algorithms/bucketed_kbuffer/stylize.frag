#version 450 core
// Stylization pass (murray2016 5.2, slot_layout=full): every stored
// fragment's colour through the transfer functions (bkb_stylize.glsl), with
// the kappa the neighbour pass kept in the features word. With both
// transfer functions identity the pass does not run at all.
#include "algorithms/bucketed_kbuffer/bkb_common.glsl"
#include "algorithms/bucketed_kbuffer/bkb_stylize.glsl"

void main() {
  uint base = bkb_pixel_base();
  for (int i = 0; i < K; ++i) {
    uint slot = base + uint(i);
    uint key = bkb_z[slot];
    if (key == BKB_EMPTY) break;
    if (bkb_normals[slot] == 0u) continue;  // no data stored (counted as a store miss)
    float kappa = unpackHalf2x16(bkb_features[slot] & 0xffffu).x;
    bkb_colors[slot] = bkb_stylize(bkb_colors[slot], kappa, key);
  }
}
