#version 450 core
// Sort (carnecky2013 section 4.3): one invocation per pixel (per covered
// pixel with storage=linearized, pixel_dispatch.glsl) gathers its list
// into a local array ordered by (view depth, stable triangle id), reserves a
// contiguous range of fragData2/fragData3 with one atomic add (the range's
// first index and length replace pixelHead and pixelCount) and copies the
// records there in order. Lists longer than IB_ARRAY keep their IB_ARRAY
// nearest fragments (the fill counted the rest as dropped): that path
// (IB_TRUNCATES) is compiled only for frames with such a list, as llvmpipe
// runs a branch's code even where no lane takes it. Lists of 0 or 1 fragments skip
// the walk and the sort.
//
// IB_DYNAMIC (sort=dynamic): pastyrik2016 Algorithm 2 instead of the array.
// The list is insertion-sorted in the buffers: each node is unlinked from
// the fill's list (its old `next` kept in a register, so one next buffer
// serves both lists, where the paper keeps a second one) and linked into a
// sorted list at the first node it precedes; then the nearest max_per_pixel
// nodes are copied as above. Equal keys keep list order in both variants,
// so the records are the same.
//
// IB_STATIC_ARRAYS (sort=static_arrays): pastyrik2016 section 3.2's
// "Sorting in Array of Fixed Size" as its section 4.1 measured it: three
// local arrays of IB_STATIC_ENTRIES (64) whatever the frame's lists, the
// list loaded into them, selection-sorted, and copied out as above
// (sort_static_arrays below).
//
// IB_RANGED (storage=linearized or arrays): the pixel's fill records are
// contiguous (fill.frag), read in order with no list walk, and the sorted
// range is the one the host computed from the kept lengths (ib_head,
// ib_count): no atomic. The dispatch is over the pixels that hold a fragment
// (pixel_dispatch.glsl, IB_LISTED). linearized: the range
// [offset[p], offset[p+1]), and the host checks that every pixel's fill
// ended at the end of its counted range (SlotCursors::count_mismatched: the
// counting pass and the fill disagreed). IB_ARRAYS: the first count[p] of
// the ib.slots records from p * ib.slots, count[p] the fill's final cursor
// (the host filled again until every list fit).
//
// The list is walked by ONE flat loop: each iteration either takes the next
// node or moves the pending node's insertion hole one step nearer. Mesa 22.3
// llvmpipe miscompiled nested loops following `next` pointers (only the head
// was visited), so nothing here nests a list walk.
#include "algorithms/illustration_buffer/ib_storage.glsl"
#include "algorithms/illustration_buffer/pixel_dispatch.glsl"

// fragData (3 RGBA32UI texels per IbFragment) read as a buffer texture:
// gathers on llvmpipe, where SSBO loads at per-invocation addresses run
// lane by lane (see views.glsl). The fill's list links are in the key texel.
layout(binding = IB_FRAGMENT_UNIT) uniform usamplerBuffer ib_fragment_view;
#ifdef IB_TRIANGLE_VERTICES
// neighbors=triangle_index: the sorted record's geometry holds the vertex
// indices of the fragment's triangle instead of the normal and the slopes
// (which only the heuristic reads), so that the search reads one texel per
// candidate instead of the key and then the triangle's row.
layout(binding = IB_SORT_TRIANGLES_UNIT) uniform usamplerBuffer ib_triangle_rows;
#endif

#if defined(IB_ARRAYS)
layout(binding = IB_OFFSETS_UNIT) uniform usamplerBuffer ib_fill_counts;  // W*H values
#elif defined(IB_RANGED)
layout(binding = IB_OFFSETS_UNIT) uniform usamplerBuffer ib_offsets;  // W*H + 1 values
#endif
#ifdef IB_RANGED
// The fill record after `node` in the pixel's list (`taken`: sort_key(node)).
#define IB_FOLLOW(node, taken) ((node) + 1u)
#else
#define IB_FOLLOW(node, taken) ((taken).w)
#endif

// The first index of the pixel's sorted range of `kept` records.
uint sorted_range(uint pixel, uint kept) {
#ifdef IB_RANGED
  return ib_head[pixel];  // the prefix sum of the kept lengths (host)
#else
  const uint first = kept == 0u ? 0u : atomicAdd(ib_allocated, kept);
  ib_head[pixel] = first;
  ib_count[pixel] = kept;
  return first;
#endif
}

#ifdef IB_FLAT_COLOR
// flat_color_records (unlit scenes; lit ones with IB_RANGED): the fill stored
// no colour; each fragment's is its triangle's flat colour, by stable
// triangle id (SceneGpu), with IB_RANGED times the light factor in key.w.
layout(binding = IB_FLAT_COLORS_UNIT) uniform samplerBuffer ib_flat_colors;
#endif

bool precedes(uvec3 a, uvec3 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

// Copies fill record `node` of `pixel` to sorted position `to`.
void copy_record(uint to, uint node, uint pixel) {
  const uvec4 key = texelFetch(ib_fragment_view, int(node * IB_FILL_TEXELS + IB_FILL_KEY_TEXEL));
#if defined(IB_FLAT_COLOR) && defined(IB_RANGED)
  const vec4 flat_color = texelFetch(ib_flat_colors, int(key.y));
  const vec4 color = vec4(flat_color.rgb * uintBitsToFloat(key.w), flat_color.a);  // IB_FILL_RANGED: the light factor
#elif defined(IB_FLAT_COLOR)
  const vec4 color = texelFetch(ib_flat_colors, int(key.y));
#else
  const vec4 color = uintBitsToFloat(texelFetch(ib_fragment_view, int(node * IB_FILL_TEXELS + IB_FILL_COLOR_TEXEL)));
#endif
#if defined(IB_TRIANGLE_VERTICES)  // the geometry layouts of bindings.h
  const uvec4 geometry = uvec4(texelFetch(ib_triangle_rows, int(key.y)).xyz, node);
#elif defined(IB_SURFACE)
  const uvec4 surface = texelFetch(ib_fragment_view, int(node * IB_FILL_TEXELS + IB_FILL_SURFACE_TEXEL));
  const uvec4 geometry = uvec4(surface.w, surface.x, surface.y, node);
#else
  const uvec4 geometry = uvec4(0u, 0u, 0u, node);  // the fill recorded no surface (Settings::records_surface)
#endif
  ib_search[to] = IbSortedSearch(uvec4(key.xyz, pixel), geometry);
  ib_shade[to].color = color;  // the links are the neighbour search's (modulated modes only)
}

// The sort key of fill record `node`: x depth order bits, y stable triangle
// id, z the node; and w the next node of the fill's list.
uvec4 sort_key(uint node) {
  const uvec4 key = texelFetch(ib_fragment_view, int(node * IB_FILL_TEXELS + IB_FILL_KEY_TEXEL));
  return uvec4(ib_depth_order(key.x), key.y, node, key.w);
}

#ifdef IB_DYNAMIC

// Sorts the list of `length` (>= 2) nodes from `head` in place; returns the sorted head.
// One flat loop: each step takes the next unsorted node, or moves the
// insertion point one node along the sorted list.
uint sort_list(uint head) {
  uint unsorted = head, sorted = IB_NIL, previous = IB_NIL;
  uvec3 pending = uvec3(IB_NIL);  // z: the node being inserted after `previous`, IB_NIL: none
  while (unsorted != IB_NIL || pending.z != IB_NIL) {
    if (pending.z == IB_NIL) {
      const uvec4 taken = sort_key(unsorted);
      pending = taken.xyz;
      unsorted = taken.w;
      if (sorted == IB_NIL || precedes(pending, sort_key(sorted).xyz)) {
        ib_next[pending.z] = sorted;
        sorted = pending.z;
        pending.z = IB_NIL;
      } else {
        previous = sorted;
      }
    } else {
      const uint after = ib_next[previous];
      if (after != IB_NIL && !precedes(pending, sort_key(after).xyz)) {
        previous = after;
      } else {
        ib_next[pending.z] = after;
        ib_next[previous] = pending.z;
        pending.z = IB_NIL;
      }
    }
  }
  return sorted;
}
#endif

#ifdef IB_STATIC_ARRAYS
#include "algorithms/illustration_buffer/sort_static_arrays.glsl"
#endif

#if !defined(IB_DYNAMIC) && !defined(IB_STATIC_ARRAYS)
// The whole list fits the array: each fragment is copied to its rank, the
// number of fragments before it in (depth, triangle) order, ties in list
// order. The keys are gathered into a local array first; every array index
// is a loop counter, the same in all lanes, so llvmpipe reads the array as
// vectors, where the insertion of keep_nearest moves a per-lane hole (a
// gather and a scatter per step). Short contiguous lists
// (storage=linearized or arrays; local arrays of at most 4) re-read the keys
// instead, which is faster for lists that short.
#if defined(IB_RANGED) && IB_ARRAY <= 4
#define IB_GATHER_KEYS(start, length)
#define IB_ITEM(k) sort_key(start + (k)).xyz  // `start`: sort_whole_list's
#else
#define IB_GATHER_KEYS(start, length)              \
  uvec3 items[IB_ARRAY];                           \
  for (uint k = 0u, node = start; k < length; ++k) { \
    const uvec4 taken = sort_key(node);            \
    items[k] = taken.xyz;                          \
    node = IB_FOLLOW(node, taken);                 \
  }
#define IB_ITEM(k) items[k]
#endif
void sort_whole_list(uint start, uint length, uint pixel) {
  IB_GATHER_KEYS(start, length)
  const uint first = sorted_range(pixel, length);
  for (uint i = 0u; i < length; ++i) {
    const uvec3 mine = IB_ITEM(i);  // z: its fill record
    uint rank = 0u;
    for (uint j = 0u; j < length; ++j) {
      const uvec3 other = IB_ITEM(j);
      rank += precedes(other, mine) || (j < i && other.xy == mine.xy) ? 1u : 0u;
    }
    copy_record(first + rank, mine.z, pixel);
  }
}

#ifdef IB_TRUNCATES
// A list longer than the array (some list of the frame is longer than
// max_per_pixel): insertion-sorts it through the array, which keeps the
// IB_ARRAY nearest fragments.
void keep_nearest(uint start, uint length, uint pixel) {
  uvec3 items[IB_ARRAY];
  uint node = start, taken_count = 0u, kept = 0u;
  int hole = -1;  // where `pending` goes; -1: nothing being inserted
  uvec3 pending = uvec3(0u);
  while (taken_count < length || hole >= 0) {
    if (hole < 0) {
      const uvec4 taken = sort_key(node);
      pending = taken.xyz;
      node = IB_FOLLOW(node, taken);
      ++taken_count;
      // Enters at the end while there is room, else replaces the farthest
      // kept fragment when nearer, else is left out (counted by the fill).
      if (kept < uint(IB_ARRAY)) {
        hole = int(kept);
        ++kept;
      } else if (precedes(pending, items[IB_ARRAY - 1])) {
        hole = IB_ARRAY - 1;
      }
    } else if (hole > 0 && precedes(pending, items[hole - 1])) {
      items[hole] = items[hole - 1];
      --hole;
    } else {
      items[hole] = pending;
      hole = -1;
    }
  }
  const uint first = sorted_range(pixel, kept);
  for (uint i = 0u; i < kept; ++i) copy_record(first + i, items[i].z, pixel);
}
#endif
#endif

void main() {
  uint pixel;
  if (!ib_invocation_pixel(pixel)) return;
#if defined(IB_ARRAYS)
  const uint start = pixel * ib.slots;
  const uint length = texelFetch(ib_fill_counts, int(pixel)).x;
#elif defined(IB_RANGED)
  const uint start = texelFetch(ib_offsets, int(pixel)).x;
  const uint length = texelFetch(ib_offsets, int(pixel) + 1).x - start;
#else
  const uint start = ib_head[pixel];
  const uint length = ib_count[pixel];
#endif
  // Lists of 0 or 1 fragments (the fill's count) have nothing to sort: no
  // local array, no list walk; the one record is copied as it is.
  if (length <= 1u) {
    const uint only = sorted_range(pixel, length);
    if (length == 1u) copy_record(only, start, pixel);
    return;
  }
#ifdef IB_DYNAMIC
  const uint kept = min(length, ib.max_per_pixel);
  uint node = sort_list(start);
  const uint first = sorted_range(pixel, kept);
  for (uint i = 0u; i < kept; ++i) {
    copy_record(first + i, node, pixel);
    node = ib_next[node];
  }
#elif defined(IB_STATIC_ARRAYS)
  sort_static_arrays(start, length, pixel);
#else
#ifdef IB_TRUNCATES
  if (length > uint(IB_ARRAY)) {
    keep_nearest(start, length, pixel);
    return;
  }
#endif
  sort_whole_list(start, length, pixel);
#endif
}
