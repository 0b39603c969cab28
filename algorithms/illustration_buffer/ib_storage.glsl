// The illustration buffer (carnecky2013 section 4.1, pastyrik2016 section 3):
// per-pixel head/count, per-fragment next pointers and records, the sorted
// contiguous copy fragData2 + fragData3, global counters and the triangle table.
// Records are read and written as whole vec4/uvec4 members: on Mesa 22.3
// llvmpipe, reading single scalar members of a struct array in a loop
// returned wrong values.
#include "algorithms/illustration_buffer/bindings.h"

#define IB_INFINITY 3.0e38

// fragData: one record per fragment in fill order (48 B), laid out as
// bindings.h names it (IB_FILL_LINKED / IB_FILL_RANGED). In the linked
// lists the link sits in the key, so the sort's walk reads one texel per node.
struct IbFragment {
  vec4 color;
  uvec4 key;
  uvec4 surface;
};

// The sorted lists, each pixel's fragments contiguous, nearest first, split
// over two buffers of 32 B per record (together 64 B; one 64 B array would
// pass llvmpipe's 128 MiB storage-block limit at 2.1M fragments):
// fragData2: what the neighbour search compares.
// (bindings.h: IB_GEOMETRY_SURFACE / IB_GEOMETRY_TRIANGLE / IB_GEOMETRY_NONE).
struct IbSortedSearch {
  uvec4 key;
  uvec4 geometry;
};
// fragData3: what stylize and compose read, and the links the search writes.
struct IbSortedShade {
  vec4 color;
  uvec4 links;
};

layout(std430, binding = IB_HEAD_BINDING) coherent buffer IbPixelHead { uint ib_head[]; };
layout(std430, binding = IB_COUNT_BINDING) coherent buffer IbPixelCount { uint ib_count[]; };
// sort=dynamic's sorted lists (the fill's links are IbFragment::key.w).
layout(std430, binding = IB_NEXT_BINDING) buffer IbFragNext { uint ib_next[]; };
layout(std430, binding = IB_DATA_BINDING) buffer IbFragData { IbFragment ib_fragments[]; };
layout(std430, binding = IB_DATA2_BINDING) buffer IbFragData2 { IbSortedSearch ib_search[]; };
layout(std430, binding = IB_DATA3_BINDING) buffer IbFragData3 { IbSortedShade ib_shade[]; };
// produced: fragments the fill generated (may exceed the pool: overflow).
// longest: the longest list. dropped / truncated: fragments beyond
// max_per_pixel and the lists that had any. allocated: the sort's range
// allocator (storage=linked; the host counts all of these for linearized).
layout(std430, binding = IB_COUNTERS_BINDING) coherent buffer IbCounters {
  uint ib_produced;
  uint ib_longest;
  uint ib_dropped;
  uint ib_truncated;
  uint ib_allocated;
};

// The parameters of the frame and of the pass (bindings.h, frame_params.h).
layout(std140, binding = IB_FRAME_PARAMS_BLOCK) uniform IbFrameBlock { IbFrameParams ib; };
layout(std140, binding = IB_PASS_PARAMS_BLOCK) uniform IbPassBlock { IbPassParams ib_pass; };


// The sort key's first word: IEEE floats compare like sign-magnitude
// integers; this maps them to unsigned order.
uint ib_depth_order(uint bits) { return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u; }

// Octahedral normal encoding in two snorm16: 4 bytes, error ~1e-4 rad.
uint ib_pack_normal(vec3 n) {
  if (any(isnan(n))) n = vec3(0.0, 0.0, 1.0);
  n /= max(abs(n.x) + abs(n.y) + abs(n.z), 1e-30);
  vec2 e = n.xy;
  if (n.z < 0.0) e = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return packSnorm2x16(e);
}

vec3 ib_unpack_normal(uint bits) {
  vec2 e = unpackSnorm2x16(bits);
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  float t = max(-n.z, 0.0);
  n.x += n.x >= 0.0 ? -t : t;
  n.y += n.y >= 0.0 ? -t : t;
  return normalize(n);
}
