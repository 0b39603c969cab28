#version 450 core
// Length classes of the network resolve (length_classes.h): one invocation
// per 4x4 screen tile finds the longest list in its tile, picks the smallest
// class (network size) that holds it, and appends the tile to that class's
// list, counting it in the class's indirect draw command. tile.vert then
// draws each class as one point per tile with the network of its size.
// LL_TILE (tile side), LL_CLASS_COUNT and LL_CLASS_SIZES (increasing network
// sizes, as a uint array) are injected by length_classes.cpp.
layout(local_size_x = 64) in;

#include "algorithms/linked_list/bindings.h"

layout(binding = LINKED_LIST_LENGTHS_UNIT) uniform usamplerBuffer u_lengths;

// One DrawArraysIndirectCommand per class: vertex count (1), instance count
// (its tiles, counted here), first vertex, base instance.
layout(std430, binding = LINKED_LIST_CLASS_COMMANDS_BINDING) coherent buffer LinkedListClassCommands { uvec4 ll_commands[]; };
// Class c's tiles are ll_class_tiles[c * tile_count .. c * tile_count + instances).
layout(std430, binding = LINKED_LIST_CLASS_TILES_BINDING) writeonly buffer LinkedListClassTiles { uint ll_class_tiles[]; };

layout(std140, binding = LINKED_LIST_CLASSES_PARAMS_BLOCK) uniform LengthClassesBlock { LengthClassesParams classes; };

const uint kClassSizes[LL_CLASS_COUNT] = LL_CLASS_SIZES;

void main() {
  const ivec2 size = ivec2(classes.width, classes.height);
  const ivec2 tiles = (size + LL_TILE - 1) / LL_TILE;
  const uint tile_count = uint(tiles.x * tiles.y);
  const uint tile = gl_GlobalInvocationID.x;
  if (tile >= tile_count) return;
  const ivec2 origin = ivec2(int(tile) % tiles.x, int(tile) / tiles.x) * LL_TILE;
  const ivec2 end = min(origin + LL_TILE, size);
  uint longest = 0u;
  for (int y = origin.y; y < end.y; ++y) {
    for (int x = origin.x; x < end.x; ++x) longest = max(longest, texelFetch(u_lengths, y * size.x + x).x);
  }
  // Lists longer than the largest class are truncated: the resolve skips
  // them (the truncating draw composites them), so any class will do.
  uint c = 0u;
  while (c + 1u < uint(LL_CLASS_COUNT) && kClassSizes[c] < longest) ++c;
  const uint slot = atomicAdd(ll_commands[c].y, 1u);
  ll_class_tiles[c * tile_count + slot] = tile;
}
