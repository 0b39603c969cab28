#pragma once
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "harness/gl/handles.h"

namespace oit {

// A #define injected after the #version line, e.g. {"K", "16"}.
using ShaderDefine = std::pair<std::string, std::string>;
using ShaderDefines = std::vector<ShaderDefine>;

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

}  // namespace oit
