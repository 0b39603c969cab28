#version 450 core
// Pass 1 (fill): insert this fragment's depth key into the pixel's k sorted
// slots by repeated atomicMin. Each slot keeps the smaller of (its value,
// the travelling key) and the larger one travels on, so concurrent inserts
// keep every slot's multiset intact and the K smallest keys end up sorted.
// A key that travels past slot K-1 belongs to a fragment beyond the K
// nearest; the store pass decides its fate (drop or tail blend).
#include "shaders/shading.glsl"
#include "algorithms/kbuffer/kbuffer_storage.glsl"

void main() {
  const uint first = kbuffer_first_slot();
  uint key = kbuffer_depth_key(oit_view_depth());
  // Skip, with plain reads, the prefix of slots already below the key. Safe
  // because (1) a slot only ever decreases, and (2) the slots are sorted at
  // every instant (a key carried into slot i+1 is >= what slot i holds then
  // and later). So a slot read as < key stays < key, as does every slot
  // before it, and atomicMin there would return a smaller value and leave
  // both the slot and the key unchanged. A fragment behind all K nearest
  // thus costs log2(K) reads and no atomic.
  uint low = 0u, high = uint(slots.k);
  while (low < high) {
    const uint middle = (low + high) >> 1;
    if (kbuffer_keys[first + middle] < key) low = middle + 1u;
    else high = middle;
  }
  for (uint i = low; i < uint(slots.k); ++i) {
    const uint previous = atomicMin(kbuffer_keys[first + i], key);
    if (previous == KBUFFER_EMPTY) return;  // took an empty slot: nothing left to carry
    key = max(key, previous);
  }
}
