#version 450 core
// Second resolve draw, only for pixels whose list is longer than the local
// array of resolve.frag (LL_CAPACITY = max_per_pixel), drawn only when the
// fill counted dropped fragments. Keeps the LL_CAPACITY nearest fragments by
// inserting each one into a sorted, bounded array while the list is walked
// (Yang et al.'s insertion during traversal); the fill counted the others as
// dropped. Same sort key and float blend as resolve.frag.
#include "algorithms/linked_list/resolve_common.glsl"

uvec3 items[LL_CAPACITY];

void main() {
  const uint pixel = ll_pixel();
  if (length_of(pixel) <= uint(LL_CAPACITY)) discard;  // resolve.frag did it
  uint kept = 0u;
  // The pixel's LL_HEADS lists (nodes.glsl) are walked one after the other.
  const uvec4 heads = heads_of(pixel);
  uint list = 0u;
  uint cursor = heads.x;
  // One flat loop: each iteration either moves on to the next list, takes
  // the next fragment or moves the hole of the fragment being inserted one
  // step nearer (a shift loop nested in the list walk is miscompiled by
  // llvmpipe).
  int hole = -1;  // where `candidate` would go; -1: no insertion under way
  uvec3 candidate = uvec3(0u);
  while (list < uint(LL_HEADS) || hole >= 0) {
    if (hole < 0 && cursor == LL_NIL) {
      ++list;
      cursor = list < uint(LL_HEADS) ? heads[min(list, uint(LL_HEADS) - 1u)] : LL_NIL;
    } else if (hole < 0) {
      const uvec4 link = link_of(cursor);
      candidate = sort_element(cursor, link);
      cursor = link.z;
      // It enters at the end while there is room, else replaces the
      // farthest kept fragment if it is nearer, else it is dropped.
      if (kept < uint(LL_CAPACITY)) {
        hole = int(kept);
        ++kept;
      } else if (precedes(candidate, items[LL_CAPACITY - 1])) {
        hole = LL_CAPACITY - 1;
      }
    } else if (hole > 0 && precedes(candidate, items[hole - 1])) {
      items[hole] = items[hole - 1];
      --hole;
    } else {
      items[hole] = candidate;
      hole = -1;
    }
  }
  for (uint i = 0u; i < kept; ++i) blend(items[i].z);
  out_color = oit_finish(accumulated, transmittance);
}
