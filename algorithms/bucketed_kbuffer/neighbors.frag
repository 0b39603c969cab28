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
// the same links.
//
// Why the brute force is slower than buckets=on on a one-object scene on
// llvmpipe, although both visit the same slots: its candidate loop has the
// constant bound K (break at the first BKB_EMPTY), so the compiler unrolls
// it into K copies, and llvmpipe runs a SIMD group of fragments in lockstep
// with masked lanes: every copy executes for the whole group even after all
// lanes have met BKB_EMPTY (inferred from the timing below; the compiled code
// was not inspected). Measured (torus 256x256, k = 16, medians): the
// same brute force with a bound the compiler cannot see took 12.5 ms instead
// of 19.9 ms (buckets=on 11.1 ms); the rest is the extra BKB_EMPTY read and
// the shape tests. The single-bucket path therefore bounds its loops by the
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

layout(location = BKB_INVERSE_PROJECTION_LOCATION) uniform mat4 u_inverse_projection;
layout(location = BKB_CURVATURE_SCALE_LOCATION) uniform float u_curvature_scale;

const float kNoCandidate = 3.0e38;

uint own_keys[K];
vec3 own_normals[K];
uint own_count;

float continuity(vec3 normal_a, float depth_a, vec3 normal_b, float depth_b) {
  float dz = depth_a - depth_b;
  return (1.0 - dot(normal_a, normal_b)) + dz * dz;
}

// The view-space ray through a pixel centre as origin + direction * view
// depth (orthographic or perspective alike: the ray is a line in view space).
struct Ray {
  vec3 origin, direction;
};
Ray pixel_ray(ivec2 pixel) {
  vec2 ndc = (vec2(pixel) + 0.5) / vec2(u_width, u_height) * 2.0 - 1.0;
  vec4 near_point = u_inverse_projection * vec4(ndc, -1.0, 1.0);
  vec4 far_point = u_inverse_projection * vec4(ndc, 1.0, 1.0);
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
  return q.x < 0 || q.y < 0 || q.x >= u_width || q.y >= u_height ? BKB_EMPTY : bkb_pixel_base(q);
}

// The linked neighbour of own fragment i among the slots `range` of the
// adjacent pixel at `nb`: its slot (0xff when missing), normal (x, y) and
// view-space (X, Y). Called once per direction (no dynamically indexed
// local arrays for the four directions).
uint find_neighbour(uint i, uvec2 own_range, uint nb, uvec2 range, Ray ray, out vec2 normal_xy,
                    out vec2 position_xy) {
  normal_xy = vec2(0.0);
  position_xy = vec2(0.0);
  if (nb == BKB_EMPTY) return 0xffu;
  uint shape = bkb_shape(own_keys[i]);
  float depth_i = bkb_depth_unit(own_keys[i]);
  vec3 normal_i = own_normals[i];
  uint best = 0xffu, best_key = 0u;
  float best_eps = kNoCandidate;
  vec3 best_normal = vec3(0.0);
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
    if (eps < best_eps) {
      best_eps = eps;
      best = j;
      best_key = key;
      best_normal = normal_j;
    }
  }
  if (best == 0xffu) return 0xffu;
  // Reverse check: no other fragment of this pixel is closer to the candidate.
  float best_depth = bkb_depth_unit(best_key);
  for (uint i2 = own_range.x; i2 <= own_range.y; ++i2) {
    float eps = continuity(own_normals[i2], bkb_depth_unit(own_keys[i2]), best_normal, best_depth);
#if BUCKETS == BKB_BUCKETS_NONE
    if (bkb_shape(own_keys[i2]) != shape) eps = kNoCandidate;
#endif
    if (eps < best_eps) return 0xffu;
  }
  normal_xy = best_normal.xy;
  position_xy = (ray.origin + ray.direction * bkb_view_depth(best_key)).xy;
  return best;
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  uint base = bkb_pixel_base(pixel);
  own_count = 0u;
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
  for (uint i = 0u; i < own_count; ++i) {
#if BUCKETS == BKB_BUCKETS_SINGLE
    if (i == 0u) {
      // One bucket per pixel: the adjacent pixels' whole lists, found once
      // and only by pixels that kept a fragment.
      range_left = base_left == BKB_EMPTY ? uvec2(1u, 0u) : bkb_whole_list(base_left);
      range_right = base_right == BKB_EMPTY ? uvec2(1u, 0u) : bkb_whole_list(base_right);
      range_down = base_down == BKB_EMPTY ? uvec2(1u, 0u) : bkb_whole_list(base_down);
      range_up = base_up == BKB_EMPTY ? uvec2(1u, 0u) : bkb_whole_list(base_up);
    }
#endif
#if BUCKETS == BKB_BUCKETS_HASHED
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
    uint left = find_neighbour(i, own_range, base_left, range_left, ray_left, normal_left, position_left);
    uint right = find_neighbour(i, own_range, base_right, range_right, ray_right, normal_right, position_right);
    uint down = find_neighbour(i, own_range, base_down, range_down, ray_down, normal_down, position_down);
    uint up = find_neighbour(i, own_range, base_up, range_up, ray_up, normal_up, position_up);
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
        kappa = tanh(clamp(u_curvature_scale * curvature_sum, -20.0, 20.0));
      }
    }
    uint slot = base + i;
    bkb_features[slot] = (packHalf2x16(vec2(kappa, 0.0)) & 0xffffu) | (found << 16);
#if MEASURE_ACCURACY
    bkb_links[slot] = left | (right << 8) | (down << 16) | (up << 24);
    bkb_estimated[slot] = curvature_sum;
#endif
  }
}
