#version 450 core
// Neighbour query and curvature (murray2016 5.1). For every fragment of the
// pixel and each of the 4 adjacent pixels, the best candidate minimises
//   eps = eps_n + eps_z,  eps_n = 1 - n_i . n_j,  eps_z = |z_i - z_j|^2
// (z: depth normalised to [0, 1] by the quantisation range) among the
// candidates of the SAME shape id, and is kept only if no other fragment of
// this pixel (same shape) is closer to it: the reverse check of carnecky2013
// Algorithm 2. BUCKETS (bkb_common.glsl) picks how the candidates are found:
// BKB_BUCKETS_HASHED visits one bucket (hash look-up, Figure 4);
// BKB_BUCKETS_NONE is the brute force of Figure 10: it evaluates eps for
// every fragment of the adjacent pixel and of its own pixel and discards
// other shapes (eps = infinity, as carnecky2013 does for other components);
// BKB_BUCKETS_SINGLE (one-object scenes) visits every fragment with neither
// hash look-up nor shape test, since all share the shape. All three visit
// candidates in the same order with the same strict comparison, so they find
// the same links. SEARCH_MERGE=1 (neighbor_search=merge) replaces all three
// by a walk of both sorted lists (see merge_candidate): the same links again,
// whatever BUCKETS says. REVERSE_CHECK=0 (reverse_check=false) skips the
// reverse check: every best candidate is linked, mutual or not.
// WRITE_FEATURES=1 (slot_layout=full, or measure_accuracy) keeps kappa and
// the found mask per slot; STYLIZE_HERE=1 (slot_layout=paper with a transfer
// function) applies the transfer functions to the colour in this pass.
//
// Why the brute force is slower than buckets=on on a one-object scene on
// llvmpipe, although both visit the same slots: its candidate loop has the
// constant bound K (break at the first BKB_EMPTY), so the compiler unrolls
// it into K copies, and llvmpipe runs a SIMD group of fragments in lockstep
// with masked lanes: every copy executes for the whole group even after all
// lanes have met BKB_EMPTY (inferred from timings, README "buckets=auto on
// one object"; the compiled code was not inspected): the same brute force
// with a bound the compiler cannot see came close to buckets=on, the rest
// being the extra BKB_EMPTY read and the shape tests. The single-bucket path therefore bounds its loops by the
// list length (bkb_whole_list), never by K.
//
// Curvature (Vergne et al. 2009 style, in screen space): from the four
// linked neighbours, the 2x2 Jacobian J of the viewer-facing normal's (x, y)
// with respect to the view-space (X, Y) of the neighbours, solved exactly
// from the horizontal and vertical central differences. For a surface seen
// as a height field over the image plane, trace(J) = div(n_xy) = -(k1 + k2)
// with surfaces bulging towards the viewer negative (the paper: -1 convex,
// +1 concave). kappa = tanh(scale * (k1 + k2)); a missing neighbour gives -1.
#include "algorithms/bucketed_kbuffer/bkb_common.glsl"
#if STYLIZE_HERE
#include "algorithms/bucketed_kbuffer/bkb_stylize.glsl"
#endif

const float kNoCandidate = 3.0e38;

uint own_keys[K];
vec3 own_normals[K];
uint own_count;
// K as a value the compiler cannot see (bkb.width > 0): the merge search's
// loops stop at the first empty slot or other shape long before K, and a
// constant bound would let them be unrolled into K masked copies (see the
// brute force above).
uint slot_bound;

// `precise`: the search and the reverse check evaluate this at different
// call sites; a compiler free to fuse multiply-adds differently at each
// gave the same pair two values a rounding apart, so near-ties were broken
// one way by the search and the other by the reverse check, and links that
// passed it were not mutual (NVIDIA 580 on an H200: 89 of 29,695 on the
// cylinders at 64x64, none on llvmpipe).
float continuity(vec3 normal_a, float depth_a, vec3 normal_b, float depth_b) {
  precise float dz = depth_a - depth_b;
  precise float eps = (1.0 - dot(normal_a, normal_b)) + dz * dz;
  return eps;
}

// The view-space ray through a pixel centre as origin + direction * view
// depth (orthographic or perspective alike: the ray is a line in view space).
struct Ray {
  vec3 origin, direction;
};
Ray pixel_ray(ivec2 pixel) {
  vec2 ndc = (vec2(pixel) + 0.5) / vec2(bkb.width, bkb.height) * 2.0 - 1.0;
  vec4 near_point = bkb.inverse_projection * vec4(ndc, -1.0, 1.0);
  vec4 far_point = bkb.inverse_projection * vec4(ndc, 1.0, 1.0);
  vec3 a = near_point.xyz / near_point.w, b = far_point.xyz / far_point.w;
  vec3 direction = (b - a) / (a.z - b.z);
  return Ray(a + direction * a.z, direction);
}

// The range of `shape`'s bucket in the pixel whose list starts at `base`
// (BKB_EMPTY: outside the image); empty (x > y) when there is none.
uvec2 bucket_range(uint base, uint shape) {
  uvec2 range;
  if (base == BKB_EMPTY || !bkb_find_bucket(base, shape, range)) return uvec2(1u, 0u);
  return range;
}

uint neighbour_base(ivec2 q) {
  return q.x < 0 || q.y < 0 || q.x >= bkb.width || q.y >= bkb.height ? BKB_EMPTY : bkb_pixel_base(q);
}

// The best candidate of one search: slot (0xff when none), key, eps, normal.
struct Candidate {
  uint slot, key;
  float eps;
  vec3 normal;
};

// The best candidate for own fragment i among the slots `range` of the
// adjacent pixel at `nb` (bucket or brute-force search): the first slot of
// the smallest eps, visiting slots in increasing order with a strict
// comparison.
Candidate range_candidate(uint i, uint nb, uvec2 range) {
  uint shape = bkb_shape(own_keys[i]);
  float depth_i = bkb_depth_unit(own_keys[i]);
  vec3 normal_i = own_normals[i];
  Candidate best = Candidate(0xffu, 0u, kNoCandidate, vec3(0.0));
  for (uint j = range.x; j <= range.y; ++j) {
    uint key = bkb_z[nb + j];
#if BUCKETS == BKB_BUCKETS_NONE
    if (key == BKB_EMPTY) break;
#endif
    vec3 normal_j = bkb_unpack_normal(bkb_normals[nb + j]);
    float eps = continuity(normal_i, depth_i, normal_j, bkb_depth_unit(key));
#if BUCKETS == BKB_BUCKETS_NONE
    if (bkb_shape(key) != shape) eps = kNoCandidate;
#endif
    if (eps < best.eps) best = Candidate(j, key, eps, normal_j);
  }
  return best;
}

// Merge search. eps = eps_n + dz^2 >= dz^2, so once a fragment's squared
// depth difference exceeds the best eps so far, no fragment farther along a
// depth-sorted list can win. kBoundSlack covers the one way eps can fall
// below dz^2: a dot product of two unpacked unit normals a few ulps above 1
// (|eps_n| <= ~1e-6); it only lets the walk visit a little more.
const float kBoundSlack = 1.0e-5;
bool beyond_bound(float depth_a, float depth_b, float best_eps) {
  float dz = depth_a - depth_b;
  return dz * dz > best_eps + kBoundSlack;
}

// The same candidate as range_candidate, found by walking the sorted lists
// together. Keys are shape-major, so a shape's fragments are consecutive and
// depth-ordered, and own keys increase with i: `cursor` (the adjacent list's
// first key >= own key i, BKB_EMPTY being above every key) only moves
// forward over the pixel's fragments, O(K) per pixel pair. From there the
// walk goes up (deeper) and down (nearer) within the shape until the bound
// stops it. Candidates are compared by (eps, slot), which is what the
// in-order strict comparison picks, whatever order the walk visits them in.
Candidate merge_candidate(uint i, uint nb, inout uint cursor) {
  uint own_key = own_keys[i], shape = bkb_shape(own_key);
  // The key at the cursor, kept for the upward walk (each slot read once).
  uint key = BKB_EMPTY;
  while (cursor < slot_bound) {
    key = bkb_z[nb + cursor];
    if (key >= own_key) break;
    key = BKB_EMPTY;
    ++cursor;
  }
  float depth_i = bkb_depth_unit(own_key);
  vec3 normal_i = own_normals[i];
  Candidate best = Candidate(0xffu, 0u, kNoCandidate, vec3(0.0));
  for (uint j = cursor; key != BKB_EMPTY && bkb_shape(key) == shape;) {
    float depth_j = bkb_depth_unit(key);
    if (beyond_bound(depth_j, depth_i, best.eps)) break;
    vec3 normal_j = bkb_unpack_normal(bkb_normals[nb + j]);
    float eps = continuity(normal_i, depth_i, normal_j, depth_j);
    if (eps < best.eps || (eps == best.eps && j < best.slot)) best = Candidate(j, key, eps, normal_j);
    ++j;
    key = j < slot_bound ? bkb_z[nb + j] : BKB_EMPTY;
  }
  for (uint j = cursor; j > 0u;) {
    --j;
    uint key = bkb_z[nb + j];
    if (bkb_shape(key) != shape) break;
    float depth_j = bkb_depth_unit(key);
    if (beyond_bound(depth_j, depth_i, best.eps)) break;
    vec3 normal_j = bkb_unpack_normal(bkb_normals[nb + j]);
    float eps = continuity(normal_i, depth_i, normal_j, depth_j);
    if (eps < best.eps || (eps == best.eps && j < best.slot)) best = Candidate(j, key, eps, normal_j);
  }
  return best;
}

// Reverse check (carnecky2013 Algorithm 2): false when another fragment of
// this pixel of the same shape is strictly closer to the candidate.
bool reverse_check(uint i, uvec2 own_range, Candidate best) {
  float best_depth = bkb_depth_unit(best.key);
#if SEARCH_MERGE
  // Only own fragments within the bound can be closer; they are the
  // consecutive run of the shape around i (i itself included, as below).
  uint shape = bkb_shape(own_keys[i]);
  for (uint i2 = i; i2 < own_count; ++i2) {
    if (bkb_shape(own_keys[i2]) != shape) break;
    float depth_i2 = bkb_depth_unit(own_keys[i2]);
    if (beyond_bound(depth_i2, best_depth, best.eps)) break;
    if (continuity(own_normals[i2], depth_i2, best.normal, best_depth) < best.eps) return false;
  }
  for (uint i2 = i; i2 > 0u;) {
    --i2;
    if (bkb_shape(own_keys[i2]) != shape) break;
    float depth_i2 = bkb_depth_unit(own_keys[i2]);
    if (beyond_bound(depth_i2, best_depth, best.eps)) break;
    if (continuity(own_normals[i2], depth_i2, best.normal, best_depth) < best.eps) return false;
  }
#else
  for (uint i2 = own_range.x; i2 <= own_range.y; ++i2) {
    float eps = continuity(own_normals[i2], bkb_depth_unit(own_keys[i2]), best.normal, best_depth);
#if BUCKETS == BKB_BUCKETS_NONE
    if (bkb_shape(own_keys[i2]) != bkb_shape(own_keys[i])) eps = kNoCandidate;
#endif
    if (eps < best.eps) return false;
  }
#endif
  return true;
}

// The linked neighbour of own fragment i in the adjacent pixel at `nb`
// (BKB_EMPTY: outside the image): its slot (0xff when missing), normal
// (x, y) and view-space (X, Y). Called once per direction (no dynamically
// indexed local arrays for the four directions). `range`: the slots the
// bucket/brute-force search visits; `cursor`: the merge search's position.
uint find_neighbour(uint i, uvec2 own_range, uint nb, uvec2 range, inout uint cursor, Ray ray,
                    out vec2 normal_xy, out vec2 position_xy) {
  normal_xy = vec2(0.0);
  position_xy = vec2(0.0);
  if (nb == BKB_EMPTY) return 0xffu;
#if SEARCH_MERGE
  Candidate best = merge_candidate(i, nb, cursor);
#else
  Candidate best = range_candidate(i, nb, range);
#endif
  if (best.slot == 0xffu) return 0xffu;
#if REVERSE_CHECK
  if (!reverse_check(i, own_range, best)) return 0xffu;
#endif
  normal_xy = best.normal.xy;
  position_xy = (ray.origin + ray.direction * bkb_view_depth(best.key)).xy;
  return best.slot;
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  uint base = bkb_pixel_base(pixel);
  own_count = 0u;
  slot_bound = uint(K) + uint(min(bkb.width, 0));
  for (int i = 0; i < K; ++i) {
    uint key = bkb_z[base + uint(i)];
    if (key == BKB_EMPTY) break;
    own_keys[i] = key;
    own_normals[i] = bkb_unpack_normal(bkb_normals[base + uint(i)]);
    ++own_count;
  }
  ivec2 q_left = pixel + ivec2(-1, 0), q_right = pixel + ivec2(1, 0);
  ivec2 q_down = pixel + ivec2(0, -1), q_up = pixel + ivec2(0, 1);
  uint base_left = neighbour_base(q_left), base_right = neighbour_base(q_right);
  uint base_down = neighbour_base(q_down), base_up = neighbour_base(q_up);
  Ray ray_left = pixel_ray(q_left), ray_right = pixel_ray(q_right);
  Ray ray_down = pixel_ray(q_down), ray_up = pixel_ray(q_up);
  uvec2 own_range = uvec2(0u, own_count - 1u);
  // Brute force: every slot of the adjacent pixel, every fragment of this one
  // (the other paths overwrite the ranges below).
  uvec2 all_slots = uvec2(0u, uint(K) - 1u);
  uvec2 range_left = all_slots, range_right = all_slots, range_down = all_slots, range_up = all_slots;
  uint cursor_left = 0u, cursor_right = 0u, cursor_down = 0u, cursor_up = 0u;  // merge search only
  for (uint i = 0u; i < own_count; ++i) {
#if BUCKETS == BKB_BUCKETS_SINGLE && !SEARCH_MERGE
    if (i == 0u) {
      // One bucket per pixel: the adjacent pixels' whole lists, found once
      // and only by pixels that kept a fragment.
      range_left = base_left == BKB_EMPTY ? uvec2(1u, 0u) : bkb_whole_list(base_left);
      range_right = base_right == BKB_EMPTY ? uvec2(1u, 0u) : bkb_whole_list(base_right);
      range_down = base_down == BKB_EMPTY ? uvec2(1u, 0u) : bkb_whole_list(base_down);
      range_up = base_up == BKB_EMPTY ? uvec2(1u, 0u) : bkb_whole_list(base_up);
    }
#endif
#if BUCKETS == BKB_BUCKETS_HASHED && !SEARCH_MERGE
    uint shape = bkb_shape(own_keys[i]);
    if (i == 0u || shape != bkb_shape(own_keys[i - 1u])) {
      // First fragment of one of this pixel's buckets: its range follows
      // from the sorted local list; look the shape up once in each adjacent
      // pixel's hash table for all fragments of the bucket.
      uint last = i;
      while (last + 1u < own_count && bkb_shape(own_keys[last + 1u]) == shape) ++last;
      own_range = uvec2(i, last);
      range_left = bucket_range(base_left, shape);
      range_right = bucket_range(base_right, shape);
      range_down = bucket_range(base_down, shape);
      range_up = bucket_range(base_up, shape);
    }
#endif
    vec2 normal_left, normal_right, normal_down, normal_up;
    vec2 position_left, position_right, position_down, position_up;
    uint left = find_neighbour(i, own_range, base_left, range_left, cursor_left, ray_left, normal_left, position_left);
    uint right =
        find_neighbour(i, own_range, base_right, range_right, cursor_right, ray_right, normal_right, position_right);
    uint down = find_neighbour(i, own_range, base_down, range_down, cursor_down, ray_down, normal_down, position_down);
    uint up = find_neighbour(i, own_range, base_up, range_up, cursor_up, ray_up, normal_up, position_up);
    uint found = (left != 0xffu ? 1u : 0u) | (right != 0xffu ? 2u : 0u) | (down != 0xffu ? 4u : 0u) |
                 (up != 0xffu ? 8u : 0u);
    float kappa = -1.0;
    float curvature_sum = uintBitsToFloat(0x7fc00000u);  // NaN: not measured
    if (found == 0xfu) {
      mat2 offsets = mat2(position_right - position_left, position_up - position_down);
      mat2 normal_changes = mat2(normal_right - normal_left, normal_up - normal_down);
      if (determinant(offsets) != 0.0) {
        mat2 jacobian = normal_changes * inverse(offsets);
        curvature_sum = -(jacobian[0][0] + jacobian[1][1]);
        kappa = tanh(clamp(bkb.curvature_scale * curvature_sum, -20.0, 20.0));
      }
    }
    uint slot = base + i;
    uint kappa_half = packHalf2x16(vec2(kappa, 0.0)) & 0xffffu;
#if WRITE_FEATURES
    bkb_features[slot] = kappa_half | (found << 16);
#endif
#if STYLIZE_HERE
    // slot_layout=paper: no features word to keep kappa for a later pass, so
    // this fragment's colour is stylized now, as murray2016 does. Only this
    // pixel reads its own colours, so writing them here races with nothing.
    // kappa goes through float16 as with the features word: the same image.
    if (bkb_normals[slot] != 0u)
      bkb_colors[slot] = bkb_stylize(bkb_colors[slot], unpackHalf2x16(kappa_half).x, own_keys[i]);
#endif
#if MEASURE_ACCURACY
    bkb_links[slot] = left | (right << 8) | (down << 16) | (up << 24);
    bkb_estimated[slot] = curvature_sum;
#endif
  }
}
