#include "harness/gl/uniforms.h"

namespace oit {

bool uniform_active(GLuint program, const char* name) {
  return glGetProgramResourceIndex(program, GL_UNIFORM, name) != GL_INVALID_INDEX;
}

void set_uniform(GLuint program, GLint location, GLint value) { glProgramUniform1i(program, location, value); }
void set_uniform(GLuint program, GLint location, GLuint value) { glProgramUniform1ui(program, location, value); }
void set_uniform(GLuint program, GLint location, float value) { glProgramUniform1f(program, location, value); }
void set_uniform(GLuint program, GLint location, const glm::ivec2& value) {
  glProgramUniform2i(program, location, value.x, value.y);
}
void set_uniform(GLuint program, GLint location, const glm::uvec2& value) {
  glProgramUniform2ui(program, location, value.x, value.y);
}
void set_uniform(GLuint program, GLint location, const glm::vec2& value) {
  glProgramUniform2f(program, location, value.x, value.y);
}
void set_uniform(GLuint program, GLint location, const glm::vec3& value) {
  glProgramUniform3f(program, location, value.x, value.y, value.z);
}
void set_uniform(GLuint program, GLint location, const glm::mat4& value) {
  glProgramUniformMatrix4fv(program, location, 1, GL_FALSE, &value[0][0]);
}

}  // namespace oit
