#version 450 core
// Reorder pass (murray2016 4.1 "Z reordering", 4.2): swap every key to
// shape-major (shape id | depth) and sort the pixel's list, so fragments of
// one shape become consecutive (a bucket), depth-ordered inside it. Also
// clears the pixel's normal words, which the data pass uses to claim slots.
// Gathered into a local array in one simple loop first (Mesa 22.3 llvmpipe
// miscompiles some nested loops over storage buffers).
#include "algorithms/bucketed_kbuffer/bkb_common.glsl"

uint keys[K];

void main() {
  uint base = bkb_pixel_base();
  uint count = 0u;
  for (int i = 0; i < K; ++i) {
    uint key = bkb_z[base + uint(i)];
    if (key == BKB_EMPTY) break;
    keys[i] = bkb_swap_to_shape_major(key);
    ++count;
  }
  // Insertion sort: short lists, often nearly sorted.
  for (uint i = 1u; i < count; ++i) {
    uint key = keys[i];
    int j = int(i) - 1;
    while (j >= 0 && keys[j] > key) {
      keys[j + 1] = keys[j];
      --j;
    }
    keys[j + 1] = key;
  }
  for (uint i = 0u; i < count; ++i) {
    bkb_z[base + i] = keys[i];
    bkb_normals[base + i] = 0u;
  }
#if BUCKETS == BKB_BUCKETS_SINGLE
  // No bucket pass follows (one object): the list is the pixel's one bucket
  // and its length all that the store and neighbour passes need.
  bkb_buckets[base] = count;
#endif
}
