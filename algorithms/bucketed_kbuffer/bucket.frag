#version 450 core
// Bucket pass (murray2016 4.1 "Bucket creation", 4.2): one entry per run of
// equal shape ids in the shape-major list: shape id (16 bits), first and
// last slot (8 bits each), stored in a per-pixel hash table of K slots at
// H(b) = b mod K with linear probing (a free slot always exists: at most K
// buckets). All K slots are written, so the table needs no separate clear.
#include "algorithms/bucketed_kbuffer/bkb_common.glsl"

uint shapes[K];
uint table[K];

void main() {
  uint base = bkb_pixel_base();
  uint count = 0u;
  for (int i = 0; i < K; ++i) {
    uint key = bkb_z[base + uint(i)];
    if (key == BKB_EMPTY) break;
    shapes[i] = bkb_shape(key);
    ++count;
  }
  for (int i = 0; i < K; ++i) table[i] = BKB_EMPTY;
  uint first = 0u;
  for (uint i = 0u; i < count; ++i) {
    if (i + 1u < count && shapes[i + 1u] == shapes[i]) continue;  // run goes on
    uint shape = shapes[i];
    uint slot = shape % uint(K);
    while (table[slot] != BKB_EMPTY) slot = slot + 1u == uint(K) ? 0u : slot + 1u;
    table[slot] = (shape << 16) | (first << 8) | i;
    first = i + 1u;
  }
  for (int i = 0; i < K; ++i) bkb_buckets[base + uint(i)] = table[i];
}
