#pragma once
// Length classes of the resolve (parameter length_classes). The unrolled
// network costs the same for every pixel whatever its list length, and on
// llvmpipe a loop runs as long as its longest lane, so one array sized for
// the frame's longest list makes every short list pay for it. Here the screen
// is cut into 4x4 tiles, a compute pass sorts the tiles into classes by the
// longest list in each, and every class is drawn as one square point per tile
// with the network of its size. Tiles, not per-pixel masks: on llvmpipe an
// `if` or a `discard` skips no work (every lane runs every instruction),
// while a tile no primitive covers is never shaded.
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "harness/toolkit/technique.h"
#include "harness/gl/handles.h"
#include "harness/gl/shader_program.h"
#include "harness/gl/uniform_block.h"
#include "algorithms/linked_list/bindings.h"

namespace oit::linked_list {

// Network sizes for a frame whose local array is `array_size`: the powers of
// two from `smallest` below it, then `array_size` itself.
std::vector<uint32_t> class_sizes(uint32_t smallest, uint32_t array_size);

// The index of the smallest of `sizes` (increasing) that holds `longest`;
// the last one when none does (those lists are truncated, resolved elsewhere).
size_t class_index(const std::vector<uint32_t>& sizes, uint32_t longest);

// The longest list of every kTile x kTile tile of a `width` x `height` image
// of per-pixel lengths (bottom-up rows), tiles in classify.comp's order.
std::vector<uint32_t> tile_longest(const std::vector<uint32_t>& lengths, int width, int height);

// `defines` plus the tile side, for a program of tile.vert + resolve.frag.
ShaderDefines tile_defines(ShaderDefines defines);

class LengthClasses {
 public:
  // Tile side in pixels: llvmpipe shades 4x4 blocks, and a tile of one block
  // keeps the rasterizer's order of the blocks, which is the order the fill
  // wrote the nodes in. 8x8 tiles (four blocks each) made the gather's memory
  // access jump between two block rows and cost more than they saved.
  static constexpr int kTile = 4;
  // Storage for up to `max_classes` classes of a width x height image.
  void resize(int width, int height, size_t max_classes);
  // Draws the resolve for every class of `sizes` (increasing) with
  // `program_for(size)`, a program of tile.vert + resolve.frag. One size: a
  // full-screen draw (no storage needed). Several: the tiles are classified
  // first by the lists' lengths, read through texture unit 2 (bound by the
  // caller). A scissor already enabled (the harness's scene rectangle) stays.
  void draw(const Frame& frame, const std::vector<uint32_t>& sizes,
            const std::function<GLuint(uint32_t size)>& program_for);
  // Per class: its indirect draw command (16 B) and a list of tiles (4 B each).
  uint64_t bytes_allocated() const;

 private:
  GLuint classify_program(const std::vector<uint32_t>& sizes);

  int width_ = 0, height_ = 0;
  UniformBlock<LengthClassesParams> params_{LINKED_LIST_CLASSES_PARAMS_BLOCK};
  uint32_t tile_count_ = 0;
  size_t max_classes_ = 0;
  std::map<std::string, Program> classify_;  // by class list
  Buffer commands_, class_tiles_;
  Texture class_tiles_view_;
};

}  // namespace oit::linked_list
