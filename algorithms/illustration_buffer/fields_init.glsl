// Initial and boundary conditions of the fields (carnecky2013 sections
// 5.2-5.3) for one sorted fragment, shared by stylize_init.comp (one
// invocation per fragment, after the heuristic searches) and
// neighbors_triangle_index.comp (which knows the links and the neighbours'
// layers as it finds them, so no pass of its own):
//  alpha = s (eq. 4) or 1 - (1 - s)^(1/n) (eq. 5, u_adaptive), s = the
//          fragment's own alpha, n = its pixel's fragment count;
//  fewer than 4 neighbours (adjacent pixels outside the image do not count
//          as missing) -> silhouette: beta = 1, fixed;
//  otherwise, a layer index greater than a neighbour's -> beta = 0, fixed;
//  a layer index smaller than a neighbour's -> gamma = 1, fixed (halo).
// Fields the chosen modulation does not use stay 0 and unfixed.
//
// IB_TRACK (skip_converged): the first diffusion step's worklist. A fragment
// can change in that step only if a linked neighbour's initial value differs
// from its own: alpha (eq. 8 takes the mean of the differences, exactly 0
// when they are equal), or beta / gamma of 1 (unfixed fields start at 0, and
// eq. 9 only ever raises them towards a neighbour's value). So every
// fragment with beta or gamma fixed at 1, and every fragment whose alpha
// differs from a linked neighbour's initial alpha, queues its pixel and the
// 4 adjacent pixels (the links of any fragment reading it lie there); no
// other fragment moves in the first step. Scenes without silhouettes, halos
// or alpha differences (full-screen layers) queue nothing.
// Needs ib_storage.glsl, fields.glsl and views.glsl first.
#ifdef IB_TRACK
#include "algorithms/illustration_buffer/worklist.glsl"
#endif

layout(location = IB_ADAPTIVE_LOCATION) uniform bool u_adaptive;
layout(location = IB_USE_BETA_LOCATION) uniform bool u_use_beta;
layout(location = IB_USE_GAMMA_LOCATION) uniform bool u_use_gamma;

// The adjacent pixels of the links' directions: left, right, down, up.
uvec4 ib_adjacent_pixels(uint pixel) {
  const uint row = uint(u_width);
  return uvec4(pixel - 1u, pixel + 1u, pixel - row, pixel + row);
}

// The initial alpha of a fragment of alpha s in a pixel of n fragments.
float ib_initial_alpha(float s, uint n) { return u_adaptive ? 1.0 - pow(1.0 - s, 1.0 / float(n)) : s; }

// The fields of a fragment of initial alpha `alpha` at `layer` of its list
// (0 = nearest), with `links` and the layers of its linked neighbours in
// their lists (`neighbor_layers[d]`, read only where links[d] is a fragment).
vec4 ib_initial_fields(float alpha, uint layer, uvec4 links, uvec4 neighbor_layers) {
  const bool silhouette = any(equal(links, uvec4(IB_NONE)));
  bool under_a_neighbor = false, over_a_neighbor = false;  // my layer index is greater / smaller
  for (int d = 0; d < 4; ++d) {
    if (links[d] >= IB_OFF_IMAGE) continue;
    under_a_neighbor = under_a_neighbor || neighbor_layers[d] < layer;
    over_a_neighbor = over_a_neighbor || neighbor_layers[d] > layer;
  }
  float beta = 0.0, gamma = 0.0;
  uint flags = 0u;
  if (u_use_beta && (silhouette || under_a_neighbor)) {
    beta = silhouette ? 1.0 : 0.0;  // the silhouette rule wins over the "underneath" rule
    flags |= IB_FIXED_BETA;
  }
  if (u_use_gamma && over_a_neighbor) {
    gamma = 1.0;
    flags |= IB_FIXED_GAMMA;
  }
  return vec4(alpha, beta, gamma, float(flags));
}

#ifdef IB_TRACK
// Queues the pixels around `pixel` for the first step when the fragment
// with these initial fields and links can make a neighbour move (above).
void ib_seed_diffusion(vec4 fields, uvec4 links, uint pixel) {
  bool seeds = fields.y == 1.0 || fields.z == 1.0;
  const uvec4 adjacent = ib_adjacent_pixels(pixel);
  for (int d = 0; d < 4; ++d) {
    if (links[d] >= IB_OFF_IMAGE) continue;
    const float other = ib_sorted_color(links[d]).a;
    seeds = seeds || (u_adaptive ? ib_initial_alpha(other, ib_pixel_count(adjacent[d])) : other) != fields.x;
  }
  if (seeds) ib_enqueue_around(pixel);
}
#endif
