#include "harness/toolkit/passes.h"

#include <cstdio>

#include "harness/gl/check.h"

namespace oit {

void draw_scene_pass(const Frame& frame, const Program& program, const Framebuffer& framebuffer) {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
  glViewport(0, 0, frame.width, frame.height);
  glUseProgram(program.id());
  frame.set_shared_uniforms(program.id());
  frame.scene.draw();
}

void draw_additive_scene_pass(const Frame& frame, const Program& program, const Framebuffer& framebuffer) {
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  draw_scene_pass(frame, program, framebuffer);
  glDisable(GL_BLEND);
}

void draw_weighted_blended_scene_pass(const Frame& frame, const Program& program, const Framebuffer& framebuffer) {
  glEnablei(GL_BLEND, 0);
  glEnablei(GL_BLEND, 1);
  glBlendFunci(0, GL_ONE, GL_ONE);
  glBlendFunci(1, GL_ZERO, GL_ONE_MINUS_SRC_COLOR);
  draw_scene_pass(frame, program, framebuffer);
  glDisable(GL_BLEND);
}

void draw_fullscreen_pass(const Frame& frame, const Program& program) {
  frame.bind_target();
  glUseProgram(program.id());
  frame.set_shared_uniforms(program.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

Framebuffer make_attachmentless_framebuffer(int width, int height) {
  Framebuffer framebuffer = make_framebuffer();
  glNamedFramebufferParameteri(framebuffer.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, width);
  glNamedFramebufferParameteri(framebuffer.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, height);
  return framebuffer;
}

Framebuffer make_target_framebuffer(const std::vector<const Texture*>& colors, const std::string& what,
                                    const Texture* depth) {
  Framebuffer framebuffer = make_framebuffer();
  std::vector<GLenum> buffers;
  for (const Texture* color : colors) {
    const GLenum attachment = GL_COLOR_ATTACHMENT0 + GLenum(buffers.size());
    glNamedFramebufferTexture(framebuffer.id(), attachment, color->id(), 0);
    buffers.push_back(attachment);
  }
  if (depth != nullptr) glNamedFramebufferTexture(framebuffer.id(), GL_DEPTH_ATTACHMENT, depth->id(), 0);
  if (buffers.empty()) glNamedFramebufferDrawBuffer(framebuffer.id(), GL_NONE);
  else glNamedFramebufferDrawBuffers(framebuffer.id(), GLsizei(buffers.size()), buffers.data());
  check_framebuffer_complete(framebuffer, what);
  return framebuffer;
}

void check_framebuffer_complete(const Framebuffer& framebuffer, const std::string& what) {
  const GLenum status = glCheckNamedFramebufferStatus(framebuffer.id(), GL_FRAMEBUFFER);
  if (status == GL_FRAMEBUFFER_COMPLETE) return;
  char code[16];
  std::snprintf(code, sizeof code, "0x%04X", unsigned(status));
  throw GlError(what + " is incomplete (status " + code + ")");
}

}  // namespace oit
