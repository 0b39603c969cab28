#version 450 core
// Neighbour search (carnecky2013 section 4.4): every sorted fragment looks
// for its geodesic neighbour in the list of each of the 4 adjacent pixels
// (left = x-1, right = x+1, down = y-1, up = y+1, GL window coordinates).
//  IB_HEURISTIC:      carnecky2013 Algorithm 2 with the continuity measure
//                     eq. 1-3 and the mutual check (second loop over the own list).
//  IB_TRIANGLE_INDEX: pastyrik2016 Algorithm 3: the first (nearest) fragment
//                     whose triangle shares a vertex index with this one's.
// Each search is its own loop over one contiguous range (no list walking,
// no nesting); the four directions are unrolled calls.
#include "algorithms/illustration_buffer/ib_storage.glsl"
#include "algorithms/illustration_buffer/per_fragment.glsl"
#include "algorithms/illustration_buffer/views.glsl"

#if defined(IB_HEURISTIC)
layout(location = IB_WEIGHT_Z_LOCATION) uniform float u_weight_z;
layout(location = IB_WEIGHT_N_LOCATION) uniform float u_weight_n;
layout(location = IB_INVERSE_RADIUS_LOCATION) uniform float u_inverse_radius;  // 1 / r_obj

// The parts of fragment i that eq. 1-3 use, for one direction.
struct Probe {
  float z;          // eye depth z_i
  float predicted;  // z_i + (x_j - x_i) * dz/dx_i: the depth expected one pixel away
  vec3 normal;
  uint object;      // epsilon is infinite across objects (components)
};

Probe probe(uint s, int dx, int dy) {
  const uvec4 key = ib_sorted_key(s);
  const uvec4 geometry = ib_sorted_geometry(s);
  const float z = uintBitsToFloat(key.x);
  const float slope = dx != 0 ? float(dx) * uintBitsToFloat(geometry.y) : float(dy) * uintBitsToFloat(geometry.z);
  return Probe(z, z + slope, ib_unpack_normal(geometry.x), key.z);
}

// eq. 3: w_z * eps_z (eq. 1) + w_n * eps_n (eq. 2).
float continuity(Probe i, uint j) {
  const uvec4 key = ib_sorted_key(j);
  if (key.z != i.object) return IB_INFINITY;
  const float epsilon_z = abs(i.predicted - uintBitsToFloat(key.x)) * u_inverse_radius;
  const float epsilon_n = 1.0 - dot(i.normal, ib_unpack_normal(ib_sorted_geometry(j).x));
  return u_weight_z * epsilon_z + u_weight_n * epsilon_n;
}

uint find_neighbor(uint s, uint own_pixel, int dx, int dy, uint other_pixel) {
  const Probe a = probe(s, dx, dy);
  // Best candidate for A among all B's.
  float best_measure = IB_INFINITY;
  uint best = IB_NONE;
  const uint b_first = ib_head[other_pixel], b_end = b_first + ib_count[other_pixel];
  for (uint b = b_first; b < b_end; ++b) {
    const float measure = continuity(a, b);
    if (measure < best_measure) {
      best_measure = measure;
      best = b;
    }
  }
  if (best == IB_NONE) return IB_NONE;
  // Mutual check: no other fragment of A may be a better match for the candidate.
  const uint a_first = ib_head[own_pixel], a_end = a_first + ib_count[own_pixel];
  for (uint other = a_first; other < a_end; ++other) {
    if (other != s && continuity(probe(other, dx, dy), best) < best_measure) return IB_NONE;
  }
  return best;
}

#elif defined(IB_TRIANGLE_INDEX)
// Vertex indices of every triangle by stable id: ib_triangle_view (xyz; w unused).
uint find_neighbor(uint s, uint own_pixel, int dx, int dy, uint other_pixel) {
  const uvec3 mine = texelFetch(ib_triangle_view, int(ib_sorted_key(s).y)).xyz;
  const uint b_first = ib_head[other_pixel], b_end = b_first + ib_count[other_pixel];
  for (uint b = b_first; b < b_end; ++b) {
    const uvec3 theirs = texelFetch(ib_triangle_view, int(ib_sorted_key(b).y)).xyz;
    // At least one shared vertex index: a neighbour (rules 2-4 of section 3.4).
    if (any(equal(mine, theirs.xxx)) || any(equal(mine, theirs.yyy)) || any(equal(mine, theirs.zzz))) return b;
  }
  return IB_NONE;
}
#else
#error "neighbors.comp: define IB_HEURISTIC or IB_TRIANGLE_INDEX"
#endif

uint search(uint s, uint pixel, int x, int y, int dx, int dy) {
  const int nx = x + dx, ny = y + dy;
  if (nx < 0 || ny < 0 || nx >= u_width || ny >= u_height) return IB_OFF_IMAGE;
  return find_neighbor(s, pixel, dx, dy, uint(ny) * uint(u_width) + uint(nx));
}

void main() {
  const uint s = ib_fragment_index();
  if (s >= u_fragments) return;
  const uint pixel = ib_sorted_key(s).w;
  const int x = int(pixel % uint(u_width)), y = int(pixel / uint(u_width));
  uvec4 links;
  links.x = search(s, pixel, x, y, -1, 0);
  links.y = search(s, pixel, x, y, 1, 0);
  links.z = search(s, pixel, x, y, 0, -1);
  links.w = search(s, pixel, x, y, 0, 1);
  ib_shade[s].links = links;
}
