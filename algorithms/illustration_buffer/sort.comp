#version 450 core
// Sort (carnecky2013 section 4.3): one invocation per pixel gathers its list
// into a local array ordered by (view depth, stable triangle id), reserves a
// contiguous range of fragData2/fragData3 with one atomic add (the range's
// first index and length replace pixelHead and pixelCount) and copies the
// records there in order. Lists longer than IB_ARRAY keep their IB_ARRAY
// nearest fragments (the fill counted the rest as dropped). Lists of 0 or 1
// fragments skip the walk and the sort.
//
// The list is walked by ONE flat loop: each iteration either takes the next
// node or moves the pending node's insertion hole one step nearer. Mesa 22.3
// llvmpipe miscompiled nested loops following `next` pointers (only the head
// was visited), so nothing here nests a list walk.
layout(local_size_x = 8, local_size_y = 8) in;
#include "algorithms/illustration_buffer/ib_storage.glsl"

// fragData (3 RGBA32UI texels per IbFragment) and fragNext read as buffer
// textures: gathers on llvmpipe, where SSBO loads at per-invocation
// addresses run lane by lane (see views.glsl).
layout(binding = IB_FRAGMENT_UNIT) uniform usamplerBuffer ib_fragment_view;
layout(binding = IB_NEXT_UNIT) uniform usamplerBuffer ib_next_view;

// x: depth order bits, y: stable triangle id, z: fill record index.
uvec3 items[IB_ARRAY];

bool precedes(uvec3 a, uvec3 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

// Copies fill record `node` of `pixel` to sorted position `to`.
void copy_record(uint to, uint node, uint pixel) {
  const vec4 color = uintBitsToFloat(texelFetch(ib_fragment_view, int(node * 3u)));
  const uvec4 key = texelFetch(ib_fragment_view, int(node * 3u + 1u));
  const uvec4 slopes = texelFetch(ib_fragment_view, int(node * 3u + 2u));
  ib_search[to] = IbSortedSearch(uvec4(key.xyz, pixel), uvec4(key.w, slopes.x, slopes.y, node));
  ib_shade[to] = IbSortedShade(color, uvec4(IB_NONE));
}

void main() {
  if (gl_GlobalInvocationID.x >= uint(u_width) || gl_GlobalInvocationID.y >= uint(u_height)) return;
  const uint pixel = gl_GlobalInvocationID.y * uint(u_width) + gl_GlobalInvocationID.x;
  // Lists of 0 or 1 fragments (the fill's count) have nothing to sort: no
  // local array, no list walk; the one record is copied as it is.
  const uint length = ib_count[pixel];
  if (length <= 1u) {
    const uint only = length == 0u ? 0u : atomicAdd(ib_allocated, 1u);
    if (length == 1u) copy_record(only, ib_head[pixel], pixel);
    ib_head[pixel] = only;
    return;
  }
  uint cursor = ib_head[pixel];
  uint kept = 0u;
  int hole = -1;  // where `pending` goes; -1: nothing being inserted
  uvec3 pending = uvec3(0u);
  while (cursor != IB_NIL || hole >= 0) {
    if (hole < 0) {
      const uvec4 key = texelFetch(ib_fragment_view, int(cursor * 3u + 1u));
      pending = uvec3(ib_depth_order(key.x), key.y, cursor);
      cursor = texelFetch(ib_next_view, int(cursor)).x;
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
  const uint first = atomicAdd(ib_allocated, kept);
  ib_head[pixel] = first;
  ib_count[pixel] = kept;
  for (uint i = 0u; i < kept; ++i) copy_record(first + i, items[i].z, pixel);
}
