#version 450 core
// Heuristic neighbour search (carnecky2013 section 4.4): every sorted
// fragment looks for its geodesic neighbour in the list of each of the 4
// adjacent pixels (left = x-1, right = x+1, down = y-1, up = y+1, GL window
// coordinates).
// carnecky2013 Algorithm 2 with the continuity measure eq. 1-3 and the
// mutual check (second loop over the own list). IB_MERGE
// (neighbors=heuristic_merge) finds the same candidate by a walk from the
// depth-nearest fragment.
// (neighbors=triangle_index, pastyrik2016 Algorithm 3, is
// neighbors_triangle_index.comp: one invocation per pixel.)
// Each search is its own loop over one contiguous range (no list walking,
// no nesting); the four directions are unrolled calls.
#include "algorithms/illustration_buffer/ib_storage.glsl"
#include "algorithms/illustration_buffer/per_fragment.glsl"
#include "algorithms/illustration_buffer/views.glsl"


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

// w_z * eps_z (eq. 1) of a fragment at eye depth z.
float depth_term(Probe i, float z) { return ib.weight_z * (abs(i.predicted - z) * ib.inverse_radius); }

// eq. 3: w_z * eps_z (eq. 1) + w_n * eps_n (eq. 2) of a candidate with key
// `key` and unpacked normal `normal`.
float continuity(Probe i, uvec4 key, vec3 normal) {
  if (key.z != i.object) return IB_INFINITY;
  const float epsilon_n = 1.0 - dot(i.normal, normal);
  return depth_term(i, uintBitsToFloat(key.x)) + ib.weight_n * epsilon_n;
}
// The same for sorted fragment j (its normal read only for the same object).
float continuity(Probe i, uint j, uvec4 key) {
  if (key.z != i.object) return IB_INFINITY;
  return continuity(i, key, ib_unpack_normal(ib_sorted_geometry(j).x));
}
float continuity(Probe i, uint j) { return continuity(i, j, ib_sorted_key(j)); }

// The best candidate for A among all B's [b_first, b_end).
uint scan_candidate(Probe a, uint b_first, uint b_end, out float best_measure) {
  best_measure = IB_INFINITY;
  uint best = IB_NONE;
  for (uint b = b_first; b < b_end; ++b) {
    const float measure = continuity(a, b);
    if (measure < best_measure) {
      best_measure = measure;
      best = b;
    }
  }
  return best;
}

#ifdef IB_MERGE
// eq. 3 >= w_z * eps_z, so once a fragment's depth term alone exceeds the
// best measure, no fragment farther from the predicted depth along the
// depth-sorted list can win. The slack covers the ways eq. 3 can fall below
// the depth term in floats: eps_n a few ulps below 0 (a dot product of unit
// normals just above 1, times w_n) and the rounding of the sum.
bool beyond_bound(Probe a, uvec4 key, float best_measure) {
  return depth_term(a, uintBitsToFloat(key.x)) > best_measure * (1.0 + 1.0e-5) + ib.weight_n * 1.0e-5;
}

// Scores candidate b unless it lies beyond the bound (then returns false:
// the walk stops). b replaces best when its measure is smaller or, equal, it
// comes first in the list: what the in-order strict comparison picks,
// whatever order the walk visits candidates in.
bool consider(Probe a, uint b, inout float best_measure, inout uint best) {
  const uvec4 key = ib_sorted_key(b);
  if (beyond_bound(a, key, best_measure)) return false;
  const float measure = continuity(a, b, key);
  if (measure < best_measure || (measure == best_measure && best != IB_NONE && b < best)) {
    best_measure = measure;
    best = b;
  }
  return true;
}

// Lists up to this long are scanned like the heuristic (same result): the
// binary search and the bound cost more than they save there.
const uint kScanUpTo = 8u;

// The best candidate for A among B's list [b_first, b_end), sorted by eye
// depth: a binary search for the first fragment at or behind the predicted
// depth, then walks away from it on both sides until the bound stops them.
// Other objects' fragments are passed over (eps = infinity) but do not stop
// the walk.
uint best_candidate(Probe a, uint b_first, uint b_end, out float best_measure) {
  if (b_end - b_first <= kScanUpTo) return scan_candidate(a, b_first, b_end, best_measure);
  uint low = b_first, high = b_end;
  while (low < high) {
    const uint middle = (low + high) >> 1;
    if (uintBitsToFloat(ib_sorted_key(middle).x) < a.predicted) low = middle + 1u; else high = middle;
  }
  best_measure = IB_INFINITY;
  uint best = IB_NONE;
  for (uint b = low; b < b_end && consider(a, b, best_measure, best); ++b) {}
  for (uint b = low; b > b_first && consider(a, b - 1u, best_measure, best); --b) {}
  return best;
}
#else
uint best_candidate(Probe a, uint b_first, uint b_end, out float best_measure) {
  return scan_candidate(a, b_first, b_end, best_measure);
}
#endif

uint find_neighbor(uint s, uint own_pixel, int dx, int dy, uint other_pixel) {
  const Probe a = probe(s, dx, dy);
  const uint b_first = ib_pixel_first(other_pixel), b_end = b_first + ib_pixel_count(other_pixel);
  float best_measure;
  const uint best = best_candidate(a, b_first, b_end, best_measure);
  if (best == IB_NONE) return IB_NONE;
  // Mutual check: no other fragment of A may be a better match for the
  // candidate. The candidate is read once; other objects' fragments are
  // skipped on their key (their eps is infinite, never below best_measure).
  const uvec4 best_key = ib_sorted_key(best);
  const vec3 best_normal = ib_unpack_normal(ib_sorted_geometry(best).x);
  const uint a_first = ib_pixel_first(own_pixel), a_end = a_first + ib_pixel_count(own_pixel);
  for (uint other = a_first; other < a_end; ++other) {
    if (other == s || ib_sorted_key(other).z != best_key.z) continue;
    if (continuity(probe(other, dx, dy), best_key, best_normal) < best_measure) return IB_NONE;
  }
  return best;
}


uint search(uint s, uint pixel, int x, int y, int dx, int dy) {
  const int nx = x + dx, ny = y + dy;
  if (nx < 0 || ny < 0 || nx >= ib.width || ny >= ib.height) return IB_OFF_IMAGE;
  return find_neighbor(s, pixel, dx, dy, uint(ny) * uint(ib.width) + uint(nx));
}

void main() {
  const uint s = ib_fragment_index();
  if (s >= ib.fragments) return;
  const uint pixel = ib_sorted_key(s).w;
  const int x = int(pixel % uint(ib.width)), y = int(pixel / uint(ib.width));
  uvec4 links;
  links.x = search(s, pixel, x, y, -1, 0);
  links.y = search(s, pixel, x, y, 1, 0);
  links.z = search(s, pixel, x, y, 0, -1);
  links.w = search(s, pixel, x, y, 0, 1);
  ib_shade[s].links = links;
}
