#pragma once
// The one way to set a uniform: at the location that shaders/bindings.h or
// the technique's algorithms/<id>/bindings.h fixes for C++ and GLSL alike
// (`layout(location = ...)`), with the GL call chosen by the value's type.
// A technique's parameters are a uniform block instead
// (harness/gl/uniform_block.h); a plain uniform is left for a value that
// changes between the draws or dispatches of one frame.
#include <glm/glm.hpp>

#include "harness/gl/gl.h"

namespace oit {

// Whether `program` uses the uniform `name`. The compiler drops the uniforms
// a program does not use (a depth-only pass has no u_lit, one variant of a
// shader no u_depth_far), and setting a location that is not active is a GL
// error; a pass that may lack a uniform checks this first. By name, not by
// location: the linker may give a sampler declared without a location the
// very location of a uniform the program dropped.
bool uniform_active(GLuint program, const char* name);

// Sets the uniform at `location` of `program` (glProgramUniform*).
void set_uniform(GLuint program, GLint location, GLint value);
void set_uniform(GLuint program, GLint location, GLuint value);
void set_uniform(GLuint program, GLint location, float value);
void set_uniform(GLuint program, GLint location, const glm::ivec2& value);
void set_uniform(GLuint program, GLint location, const glm::uvec2& value);
void set_uniform(GLuint program, GLint location, const glm::vec2& value);
void set_uniform(GLuint program, GLint location, const glm::vec3& value);
void set_uniform(GLuint program, GLint location, const glm::mat4& value);

}  // namespace oit
