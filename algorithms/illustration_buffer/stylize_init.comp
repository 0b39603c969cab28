#version 450 core
// Initial and boundary conditions (carnecky2013 sections 5.2-5.3), one
// invocation per sorted fragment:
//  alpha = s (eq. 4) or 1 - (1 - s)^(1/n) (eq. 5, IB_ADAPTIVE), s = the
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
// eq. 9 only ever raises them towards a neighbour's value; eq. 8, with
// field_diffusion=homogeneous, moves them only by differences). So every
// fragment with beta or gamma fixed at 1, and every fragment whose alpha
// differs from a linked neighbour's initial alpha, queues its pixel and the
// 4 adjacent pixels (the links of any fragment reading it lie there); no
// other fragment moves in the first step. Scenes without silhouettes, halos
// or alpha differences (full-screen layers) queue nothing.
// Llvmpipe runs the code of a branch even when no lane takes it, so:
//  - a seed only marks its pixel (ib_seeds), and stylize_seed_queue.comp
//    lists every pixel with a mark in its cross, once per pixel (queueing
//    here, five stamp checks and atomics per fragment, cost as much as the
//    init itself where no lane queued);
//  - where every triangle of the scene has one alpha and eq. 4 is used, no
//    alpha differs: that variant is compiled without IB_ALPHA_SEEDS and
//    reads no neighbour's colour.
#include "algorithms/illustration_buffer/ib_storage.glsl"
#include "algorithms/illustration_buffer/per_fragment.glsl"
#include "algorithms/illustration_buffer/fields.glsl"
#include "algorithms/illustration_buffer/views.glsl"
#ifdef IB_TRACK
layout(std430, binding = IB_SEEDS_BINDING) writeonly buffer IbSeeds { uint ib_seeds[]; };
#endif
#ifdef IB_SWEEP_INIT
// diffusion=sweep's frames: the fields as the sweeps' hop distances, which
// the compose reads (no field range is written), and a flag, 1 when some
// fragment starts with beta or gamma of 1; without one nothing can move
// (alpha cannot either where the sweeps run), and the sweeps are skipped.
layout(std430, binding = IB_SWEEP_CHANGED_BINDING) writeonly buffer IbSeeded { uint ib_seeded; };
#include "algorithms/illustration_buffer/sweep_distances.glsl"

// A field's starting distance: a seed (fixed at 1) 0, fixed at 0 far, both fixed; else far.
uint starting_distance(float value, bool held) {
  return held ? IB_DISTANCE_FIXED | (value == 1.0 ? 0u : IB_DISTANCE_FAR) : IB_DISTANCE_FAR;
}
#endif


// -1: the neighbour is nearer in its list, +1: deeper, 0: same layer or no
// neighbour. `adjacent` is the pixel of the link's direction (the link lies there).
int compare_layer(uint layer, uint link, uint adjacent) {
  if (link >= IB_OFF_IMAGE) return 0;
  const uint other = ib_layer_of(link, adjacent);
  return other < layer ? -1 : (other > layer ? 1 : 0);
}

// The initial alpha (eq. 4, or eq. 5 with IB_ADAPTIVE) of a fragment of
// alpha s in a pixel of n fragments. A define, not a uniform: llvmpipe
// would evaluate the pow for every fragment.
#ifdef IB_ADAPTIVE
float initial_alpha(float s, uint n) { return 1.0 - pow(1.0 - s, 1.0 / float(n)); }
#else
float initial_alpha(float s, uint n) { return s; }
#endif

#ifdef IB_ALPHA_SEEDS
// Whether a linked neighbour starts with another alpha (IB_TRACK, above).
bool alpha_differs(float alpha, uvec4 links, uint pixel) {
  const uint row = uint(ib.width);
  const uvec4 adjacent = uvec4(pixel - 1u, pixel + 1u, pixel - row, pixel + row);
  bool differs = false;
  for (int d = 0; d < 4; ++d) {
    if (links[d] >= IB_OFF_IMAGE) continue;
    differs = differs || initial_alpha(ib_sorted_color(links[d]).a, ib_pixel_count(adjacent[d])) != alpha;
  }
  return differs;
}
#else
bool alpha_differs(float alpha, uvec4 links, uint pixel) { return false; }
#endif

void main() {
  const uint s = ib_fragment_index();
  if (s >= ib.fragments) return;
  const uint pixel = ib_sorted_key(s).w;
  const uint layer = ib_layer_of(s, pixel);
  const uvec4 links = ib_sorted_links(s);
  const float own_alpha = ib_sorted_color(s).a;
  const float alpha = initial_alpha(own_alpha, ib_pixel_count(pixel));

  const bool silhouette = any(equal(links, uvec4(IB_NONE)));
  const uint row = uint(ib.width);  // links: left, right, down, up (neighbors.comp)
  const ivec4 order = ivec4(compare_layer(layer, links.x, pixel - 1u), compare_layer(layer, links.y, pixel + 1u),
                            compare_layer(layer, links.z, pixel - row), compare_layer(layer, links.w, pixel + row));
  const bool under_a_neighbor = any(equal(order, ivec4(-1)));  // my layer index is greater
  const bool over_a_neighbor = any(equal(order, ivec4(1)));    // my layer index is smaller

  float beta = 0.0, gamma = 0.0;
  uint flags = 0u;
  if (ib.use_beta != 0u && (silhouette || under_a_neighbor)) {
    beta = silhouette ? 1.0 : 0.0;  // the silhouette rule wins over the "underneath" rule
    flags |= IB_FIXED_BETA;
  }
  if (ib.use_gamma != 0u && over_a_neighbor) {
    gamma = 1.0;
    flags |= IB_FIXED_GAMMA;
  }
#ifndef IB_SWEEP_INIT
  ib_fields_out[s] = vec4(alpha, beta, gamma, float(flags));
#endif
#ifdef IB_TRACK
  if (beta == 1.0 || gamma == 1.0 || alpha_differs(alpha, links, pixel)) ib_seeds[pixel] = 1u;
#endif
#ifdef IB_SWEEP_INIT
  if (beta == 1.0 || gamma == 1.0) ib_seeded = 1u;
  ib_distances[s] = ib_pack_distances(uvec2(starting_distance(beta, (flags & IB_FIXED_BETA) != 0u),
                                            starting_distance(gamma, (flags & IB_FIXED_GAMMA) != 0u)));
#endif
}
