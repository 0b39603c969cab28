#pragma once
#include <stdexcept>
#include <string>
#include <vector>

#include "harness/gl/handles.h"
#include "harness/gl/shader_defines.h"

namespace oit {

struct ShaderStageSource {
  GLenum stage;      // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, GL_COMPUTE_SHADER
  std::string path;  // e.g. "algorithms/unsorted/unsorted.frag"
};

// Error raised for a compile or link failure; the message names the file
// and line of every diagnostic the driver reported.
class ShaderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Resolves #include "path" against the embedded sources (recursively, each
// file once) and inserts #line directives whose source-string numbers map
// back to file names, so driver messages can be translated.
struct PreprocessedShader {
  std::string text;
  std::vector<std::string> files;  // index = GLSL source-string number
};
PreprocessedShader preprocess_shader(const std::string& path, const ShaderDefines& defines);

// Rewrites driver diagnostics "N:LINE(COL)" / "N(LINE)" into "file:LINE".
std::string translate_shader_log(const std::string& log, const std::vector<std::string>& files);

// Compiles and links the stages, or creates the program from the binary of
// an identical one built earlier in this process (gl/program_cache.h).
Program build_program(const std::vector<ShaderStageSource>& stages, const ShaderDefines& defines = {});
// The key under which build_program caches that program on the current context.
std::string program_cache_key(const std::vector<ShaderStageSource>& stages, const ShaderDefines& defines = {});

// Convenience: shared geometry vertex shader + a technique's fragment shader.
Program build_geometry_program(const std::string& fragment_path, const ShaderDefines& defines = {});
// Shared full-screen triangle vertex shader + a fragment shader.
Program build_fullscreen_program(const std::string& fragment_path, const ShaderDefines& defines = {});
Program build_compute_program(const std::string& compute_path, const ShaderDefines& defines = {});

// How the scene a program will draw is shaded (Scene::lit). Known, it is
// compiled in: build_program defines OIT_SCENE_LIT 0 or 1 in every stage
// that includes shaders/shading.glsl, which reads it instead of the u_lit
// uniform, so the programs of an unlit scene read (and the rasterizer
// interpolates) no normal and no view position for shading. `any` keeps the
// run-time branch on u_lit, right for every scene.
enum class SceneShading { any, unlit, lit };
const char* to_string(SceneShading shading);

// Every program built while a scope lives is built for `shading` (a nested
// scope restores the outer one when it ends). The harness opens one where it
// creates and renders a technique for a scene (harness/run/runner.cpp,
// app/viewer/live_technique.cpp); programs built outside any scope are `any`.
class SceneShadingScope {
 public:
  explicit SceneShadingScope(SceneShading shading);
  ~SceneShadingScope();
  SceneShadingScope(const SceneShadingScope&) = delete;
  SceneShadingScope& operator=(const SceneShadingScope&) = delete;

 private:
  SceneShading outer_;
};
SceneShading current_scene_shading();
// What `program` was built for: build_program labels each program that
// shades and was built for a known shading (a GL object label, which dies
// with the program); `any` for every other program.
// Frame::set_shared_uniforms refuses a program built for the other shading
// than the frame's scene.
SceneShading scene_shading_of(GLuint program);

}  // namespace oit
