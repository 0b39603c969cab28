#include "algorithms/linked_list/length_classes.h"

#include <algorithm>
#include <stdexcept>

#include "harness/gl/check.h"
#include "harness/gl/uniforms.h"
#include "algorithms/linked_list/bindings.h"

namespace oit::linked_list {
namespace {

constexpr GLuint kFullScreen = 0xffffffffu;  // u_first_tile of a full-screen draw
constexpr GLsizeiptr kCommandBytes = 16;     // DrawArraysIndirectCommand
constexpr GLuint kClassifyGroup = 64;        // classify.comp's local size

void draw_class(const Frame& frame, GLuint program, GLuint first_tile) {
  glUseProgram(program);
  frame.set_shared_uniforms(program);
  set_uniform(program, LINKED_LIST_FIRST_TILE_LOCATION, first_tile);
}

}  // namespace

std::vector<uint32_t> class_sizes(uint32_t smallest, uint32_t array_size) {
  std::vector<uint32_t> sizes;
  for (uint32_t size = smallest; size < array_size; size *= 2) sizes.push_back(size);
  sizes.push_back(array_size);
  return sizes;
}

size_t class_index(const std::vector<uint32_t>& sizes, uint32_t longest) {
  size_t c = 0;
  while (c + 1 < sizes.size() && sizes[c] < longest) ++c;
  return c;
}

std::vector<uint32_t> tile_longest(const std::vector<uint32_t>& lengths, int width, int height) {
  const int tiles_x = (width + LengthClasses::kTile - 1) / LengthClasses::kTile;
  const int tiles_y = (height + LengthClasses::kTile - 1) / LengthClasses::kTile;
  std::vector<uint32_t> longest(size_t(tiles_x) * size_t(tiles_y), 0u);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      uint32_t& tile = longest[size_t(y / LengthClasses::kTile) * size_t(tiles_x) + size_t(x / LengthClasses::kTile)];
      tile = std::max(tile, lengths[size_t(y) * size_t(width) + size_t(x)]);
    }
  }
  return longest;
}

ShaderDefines tile_defines(ShaderDefines defines) {
  defines.push_back({"LL_TILE", std::to_string(LengthClasses::kTile)});
  return defines;
}

void LengthClasses::resize(int width, int height, size_t max_classes) {
  width_ = width;
  height_ = height;
  params_.values.width = width;
  params_.values.height = height;
  max_classes_ = max_classes;
  tile_count_ = uint32_t((width + kTile - 1) / kTile) * uint32_t((height + kTile - 1) / kTile);
  commands_ = make_buffer(GLsizeiptr(max_classes) * kCommandBytes);
  class_tiles_ = make_buffer(GLsizeiptr(max_classes) * tile_count_ * 4);
  class_tiles_view_ = make_buffer_texture(class_tiles_, GL_R32UI);
  gl_check("allocating the linked_list length classes");
}

uint64_t LengthClasses::bytes_allocated() const {
  return uint64_t(max_classes_) * (uint64_t(kCommandBytes) + uint64_t(tile_count_) * 4);
}

GLuint LengthClasses::classify_program(const std::vector<uint32_t>& sizes) {
  std::string list;
  for (uint32_t size : sizes) list += (list.empty() ? "" : ",") + std::to_string(size) + "u";
  auto it = classify_.find(list);
  if (it == classify_.end()) {
    Program built = build_compute_program("algorithms/linked_list/classify.comp",
                                          {{"LL_TILE", std::to_string(kTile)},
                                           {"LL_CLASS_COUNT", std::to_string(sizes.size())},
                                           {"LL_CLASS_SIZES", "uint[](" + list + ")"}});
    it = classify_.emplace(list, std::move(built)).first;
  }
  return it->second.id();
}

void LengthClasses::draw(const Frame& frame, const std::vector<uint32_t>& sizes,
                         const std::function<GLuint(uint32_t size)>& program_for) {
  params_.upload();
  if (sizes.size() == 1) {
    draw_class(frame, program_for(sizes[0]), kFullScreen);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    return;
  }
  if (sizes.empty() || sizes.size() > max_classes_)
    throw std::logic_error("linked_list: " + std::to_string(sizes.size()) + " length classes, storage for " +
                           std::to_string(max_classes_));
  // Every class starts as a draw of one point per tile, of no tiles yet.
  std::vector<GLuint> commands(sizes.size() * 4, 0u);
  for (size_t c = 0; c < sizes.size(); ++c) commands[c * 4] = 1;
  glNamedBufferSubData(commands_.id(), 0, GLsizeiptr(commands.size() * 4), commands.data());
  const GLuint classify = classify_program(sizes);
  glUseProgram(classify);
  bind_storage_buffers({{LINKED_LIST_CLASS_COMMANDS_BINDING, &commands_},
                        {LINKED_LIST_CLASS_TILES_BINDING, &class_tiles_}});
  glDispatchCompute((tile_count_ + kClassifyGroup - 1) / kClassifyGroup, 1, 1);
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);

  // The viewport covers whole tiles, so that no point's centre lies outside
  // it (such a point is culled whole); the scissor keeps the screen's edge,
  // intersected with a scissor the caller had enabled.
  const int tiles_x = (width_ + kTile - 1) / kTile, tiles_y = (height_ + kTile - 1) / kTile;
  glViewport(0, 0, tiles_x * kTile, tiles_y * kTile);
  const bool scissored = glIsEnabled(GL_SCISSOR_TEST) == GL_TRUE;
  GLint box[4] = {0, 0, width_, height_};
  if (scissored) glGetIntegerv(GL_SCISSOR_BOX, box);
  const GLint x0 = std::max(box[0], 0), y0 = std::max(box[1], 0);
  const GLint x1 = std::min(box[0] + box[2], width_), y1 = std::min(box[1] + box[3], height_);
  glEnable(GL_SCISSOR_TEST);
  glScissor(x0, y0, std::max(x1 - x0, 0), std::max(y1 - y0, 0));
  glEnable(GL_PROGRAM_POINT_SIZE);
  glBindTextureUnit(LINKED_LIST_CLASS_TILES_UNIT, class_tiles_view_.id());
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, commands_.id());
  for (size_t c = 0; c < sizes.size(); ++c) {
    draw_class(frame, program_for(sizes[c]), GLuint(c) * tile_count_);
    glDrawArraysIndirect(GL_POINTS, reinterpret_cast<const void*>(c * kCommandBytes));
  }
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  glBindTextureUnit(LINKED_LIST_CLASS_TILES_UNIT, 0);
  glDisable(GL_PROGRAM_POINT_SIZE);
  if (scissored) {
    glScissor(box[0], box[1], box[2], box[3]);
  } else {
    glDisable(GL_SCISSOR_TEST);
  }
  glViewport(0, 0, width_, height_);
}

}  // namespace oit::linked_list
