#pragma once
// The passes most techniques are made of, written once: a geometry pass of
// the whole scene into a framebuffer, a full-screen pass into the frame's
// target, and the framebuffers they draw into.
#include <string>
#include <vector>

#include "harness/toolkit/technique.h"
#include "harness/gl/handles.h"

namespace oit {

// Binds `framebuffer` with the frame's viewport and `program` with the
// frame's shared uniforms, and draws the scene. GL state (blending, depth
// test) is the caller's.
void draw_scene_pass(const Frame& frame, const Program& program, const Framebuffer& framebuffer);
// draw_scene_pass with additive blending (ONE, ONE) on every draw buffer,
// off again afterwards: the accumulation passes of the approximate techniques.
void draw_additive_scene_pass(const Frame& frame, const Program& program, const Framebuffer& framebuffer);
// draw_scene_pass into the two targets of weighted blended OIT (McGuire &
// Bavoil 2013): draw buffer 0 sums (ONE, ONE), draw buffer 1 is multiplied
// by one minus the source (ZERO, ONE_MINUS_SRC_COLOR: the product of
// 1 - alpha, the revealage); blending off again afterwards.
void draw_weighted_blended_scene_pass(const Frame& frame, const Program& program, const Framebuffer& framebuffer);

// Binds the frame's target and draws `program` over it as one full-screen
// triangle (shaders/fullscreen.vert), with the frame's shared uniforms.
void draw_fullscreen_pass(const Frame& frame, const Program& program);

// A framebuffer without attachments of the given size, for geometry passes
// that write only storage buffers.
Framebuffer make_attachmentless_framebuffer(int width, int height);

// A framebuffer drawing into `colors` (attachments 0, 1, ... in that order,
// all of them draw buffers) and, when given, `depth`; checked complete
// (`what` names it in the error).
Framebuffer make_target_framebuffer(const std::vector<const Texture*>& colors, const std::string& what,
                                    const Texture* depth = nullptr);

// Throws GlError naming `what` (e.g. "moment_oit: moment framebuffer
// (RGBA16F)") when `framebuffer` is not complete.
void check_framebuffer_complete(const Framebuffer& framebuffer, const std::string& what);

}  // namespace oit
