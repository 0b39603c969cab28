#version 450 core
// Resolve pass (one full-screen draw): gather the pixel's LL_HEADS
// interleaved lists (nodes.glsl) into a local array of LL_CAPACITY elements, sort it by (view depth, stable triangle id),
// composite front to back in float. Pixels whose list is longer than the
// array are left to resolve_truncated.frag (a second draw, only when the
// fill counted dropped fragments). With length_classes this program is drawn
// once per class over that class's 4x4 tiles (tile.vert, length_classes.h),
// so LL_CAPACITY is the smallest array that holds the tile's longest list.
//
// The lists are walked by exactly ONE loop (side by side, one node of each
// list per iteration), and nothing else here walks them.
// On Mesa 22.3 llvmpipe (seen with SSBO reads), nested loops following
// `next` pointers visited only the head, and a second loop walking the list
// that merely read the local array made the blend loop after it stop after
// one iteration. For the network a loop would also cost its speed: a loop
// around the compare-exchanges made llvmpipe keep the registers in memory,
// so the network resolve is straight-line code.
#include "algorithms/linked_list/resolve_common.glsl"

#if defined(LL_SORT_NETWORK)
// Indexed only by constants (every macro below expands to literal indices),
// so the compiler keeps the elements in registers; a runtime-indexed array
// would live in memory and be accessed lane by lane on llvmpipe.
uvec3 e[LL_CAPACITY];

// Padding sorts after every real fragment: x = 0xffffffff would need NaN depth bits.
#define LL_PAD uvec3(0xffffffffu, 0xffffffffu, LL_NIL)
#define LL_CE(i, j) { \
    const bool swap_ij = precedes(e[j], e[i]); \
    const uvec3 first_ij = swap_ij ? e[j] : e[i]; \
    e[j] = swap_ij ? e[i] : e[j]; \
    e[i] = first_ij; }
// Element i is the next node of list i % LL_HEADS: fragment position p went
// to list p % LL_HEADS, so the first `length` loads are exactly the pixel's
// nodes and consecutive loads follow different lists (independent loads).
// A dead lane loads node 0 (always allocated) and keeps the padding.
#define LL_LOAD(i) { \
    const uint at_i = cursors[(i) % LL_HEADS]; \
    const bool live_i = at_i != LL_NIL; \
    const uvec4 link_i = link_of(live_i ? at_i : 0u); \
    e[i] = live_i ? sort_element(at_i, link_i) : LL_PAD; \
    cursors[(i) % LL_HEADS] = live_i ? link_i.z : LL_NIL; }
#define LL_BLEND(i) if (e[i].z != LL_NIL) blend(e[i].z);

void main() {
  const uint pixel = ll_pixel();
  // Longer lists are resolved by resolve_truncated.frag.
  if (length_of(pixel) > uint(LL_CAPACITY)) discard;
  uvec4 cursors = heads_of(pixel);
  LL_LOAD_ALL
  LL_NETWORK
  LL_BLEND_ALL
  out_color = oit_finish(accumulated, transmittance);
}

#else
uvec3 items[LL_CAPACITY];

void main() {
  const uint pixel = ll_pixel();
  // Longer lists are resolved by resolve_truncated.frag.
  if (length_of(pixel) > uint(LL_CAPACITY)) discard;
  uint count = 0u;
  uvec4 cursors = heads_of(pixel);
  // The same gather as the network's: each iteration takes the next node of
  // every list that has one, LL_HEADS independent loads (written out, not a
  // nested loop, see above). The sort below is the classic one on the array.
#define LL_GATHER(c) \
  if (cursors[c] != LL_NIL && count < uint(LL_CAPACITY)) { \
    const uvec4 link_##c = link_of(cursors[c]); \
    items[count] = sort_element(cursors[c], link_##c); \
    ++count; \
    cursors[c] = link_##c.z; \
  }
#if LL_HEADS != 4
#error "resolve.frag: the gather is written out for four lists"
#endif
  while (count < uint(LL_CAPACITY) && any(notEqual(cursors, uvec4(LL_NIL)))) {
    LL_GATHER(0)
    LL_GATHER(1)
    LL_GATHER(2)
    LL_GATHER(3)
  }
#if defined(LL_SORT_INSERTION)
  // Yang et al.: insertion sort of the local array.
  for (uint i = 1u; i < count; ++i) {
    const uvec3 item = items[i];
    int j = int(i) - 1;
    while (j >= 0 && precedes(item, items[j])) {
      items[j + 1] = items[j];
      --j;
    }
    items[j + 1] = item;
  }
#elif defined(LL_SORT_SELECTION)
  // Carnecky et al.: selection sort, one write (swap) per output position.
  for (uint i = 0u; i + 1u < count; ++i) {
    uint nearest = i;
    for (uint j = i + 1u; j < count; ++j) {
      if (precedes(items[j], items[nearest])) nearest = j;
    }
    const uvec3 item = items[i];
    items[i] = items[nearest];
    items[nearest] = item;
  }
#else
#error "resolve.frag: define LL_SORT_INSERTION, LL_SORT_SELECTION or LL_SORT_NETWORK"
#endif
  for (uint i = 0u; i < count; ++i) blend(items[i].z);
  out_color = oit_finish(accumulated, transmittance);
}
#endif
