#version 450 core
// Vertex shader of the network resolve (length_classes.h). A class draw
// places one square point of LL_TILE pixels per instance on tile
// u_class_tiles[u_first_tile + instance] (classify.comp). A point, not two
// triangles: llvmpipe shades each primitive's 4x4 blocks separately, so a
// block split by a quad's diagonal would be shaded twice. The tiles
// partition the screen, so every pixel is resolved by exactly one class.
// u_first_tile = 0xffffffff: one triangle covering the screen instead.
#include "algorithms/linked_list/bindings.h"

layout(binding = LINKED_LIST_CLASS_TILES_UNIT) uniform usamplerBuffer u_class_tiles;
layout(std140, binding = LINKED_LIST_CLASSES_PARAMS_BLOCK) uniform LengthClassesBlock { LengthClassesParams classes; };
layout(location = LINKED_LIST_FIRST_TILE_LOCATION) uniform uint u_first_tile;

void main() {
  if (u_first_tile == 0xffffffffu) {
    const vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
    return;
  }
  // The viewport is rounded up to whole tiles (length_classes.cpp).
  const ivec2 tiles = (ivec2(classes.width, classes.height) + LL_TILE - 1) / LL_TILE;
  const int tile = int(texelFetch(u_class_tiles, int(u_first_tile) + gl_InstanceID).x);
  const vec2 centre = (vec2(tile % tiles.x, tile / tiles.x) + 0.5) / vec2(tiles);
  gl_Position = vec4(centre * 2.0 - 1.0, 0.0, 1.0);
  gl_PointSize = float(LL_TILE);
}
