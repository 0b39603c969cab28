#pragma once
// The passes after the clear of a technique that builds per-pixel state from
// every fragment in storage buffers (fill, into a framebuffer without
// attachments), weights every fragment by that state in a second geometry
// pass added into textures (store) and composes those sums (compose):
// adaptive_transparency (its visibility function) and hybrid_transparency
// (its core of the k nearest fragments). Each pass is the stage of its name;
// the caller clears and binds its buffers first.
#include <initializer_list>
#include <utility>

#include "harness/toolkit/passes.h"
#include "harness/toolkit/technique.h"
#include "harness/gl/handles.h"

namespace oit {

struct FillStoreCompose {
  const Program& fill;
  const Framebuffer& fill_target;
  const Program& store;
  const Framebuffer& store_target;  // blended additively (ONE, ONE)
  const Program& compose;
  // The store's textures, bound at their texture units for compose.
  std::initializer_list<std::pair<GLuint, const Texture*>> compose_inputs;
};

inline void draw_fill_store_compose(const Frame& frame, const FillStoreCompose& passes) {
  {
    auto fill = frame.clock.stage("fill");
    draw_scene_pass(frame, passes.fill, passes.fill_target);
  }
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  {
    auto store = frame.clock.stage("store");
    draw_additive_scene_pass(frame, passes.store, passes.store_target);
  }
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  auto compose = frame.clock.stage("compose");
  for (const auto& [unit, texture] : passes.compose_inputs) glBindTextureUnit(unit, texture->id());
  draw_fullscreen_pass(frame, passes.compose);
}

}  // namespace oit
