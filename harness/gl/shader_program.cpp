#include "harness/gl/shader_program.h"

#include <algorithm>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

#include "harness/gl/embedded_shaders.h"
#include "harness/gl/program_cache.h"
#include "harness/gl/shader_capabilities.h"

namespace oit {
namespace {

const std::string& source_of(const std::string& path, const std::string& included_from) {
  const auto& sources = embedded_shader_sources();
  auto it = sources.find(path);
  if (it == sources.end()) {
    throw ShaderError("shader file '" + path + "' not found among embedded sources" +
                      (included_from.empty() ? "" : " (included from " + included_from + ")"));
  }
  return it->second;
}

class Preprocessor {
 public:
  PreprocessedShader run(const std::string& path, const ShaderDefines& defines) {
    const std::string& text = source_of(path, "");
    std::istringstream in(text);
    std::string first_line;
    std::getline(in, first_line);
    if (first_line.rfind("#version", 0) != 0) {
      throw ShaderError(path + ":1: first line must be a #version directive");
    }
    out_ << first_line << "\n";
    for (const auto& [name, value] : defines) out_ << "#define " << name << " " << value << "\n";
    files_.push_back(path);
    included_.insert(path);
    emit_body(in, 0, 2);
    return {out_.str(), files_};
  }

 private:
  void emit_body(std::istream& in, int file_index, int first_line_number) {
    static const std::regex include_re(R"re(^\s*#\s*include\s+"([^"]+)"\s*$)re");
    out_ << "#line " << first_line_number << " " << file_index << "\n";
    std::string line;
    int line_number = first_line_number - 1;
    while (std::getline(in, line)) {
      ++line_number;
      std::smatch match;
      if (!std::regex_match(line, match, include_re)) {
        out_ << line << "\n";
        continue;
      }
      const std::string include_path = match[1];
      if (included_.insert(include_path).second) {
        const std::string& text = source_of(include_path, files_[file_index] + ":" + std::to_string(line_number));
        files_.push_back(include_path);
        std::istringstream nested(text);
        emit_body(nested, static_cast<int>(files_.size()) - 1, 1);
      }
      out_ << "#line " << line_number + 1 << " " << file_index << "\n";
    }
  }

  std::ostringstream out_;
  std::vector<std::string> files_;
  std::set<std::string> included_;
};

const char* stage_name(GLenum stage) {
  switch (stage) {
    case GL_VERTEX_SHADER: return "vertex";
    case GL_FRAGMENT_SHADER: return "fragment";
    case GL_COMPUTE_SHADER: return "compute";
    case GL_GEOMETRY_SHADER: return "geometry";
    default: return "shader";
  }
}

// The info log of a shader or program, read with its pair of getters
// (glGetShaderiv/glGetShaderInfoLog or glGetProgramiv/glGetProgramInfoLog).
template <typename GetParameter, typename GetLog>
std::string info_log(GLuint id, GetParameter get_parameter, GetLog get_log) {
  GLint length = 0;
  get_parameter(id, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
  get_log(id, length, nullptr, log.data());
  return log;
}

Shader compile(const ShaderStageSource& stage, const PreprocessedShader& pre) {
  Shader shader(glCreateShader(stage.stage));
  const char* text = pre.text.c_str();
  glShaderSource(shader.id(), 1, &text, nullptr);
  glCompileShader(shader.id());
  GLint ok = GL_FALSE;
  glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = info_log(shader.id(), glGetShaderiv, glGetShaderInfoLog);
    throw ShaderError(std::string("failed to compile ") + stage_name(stage.stage) + " shader '" + stage.path +
                      "':\n" + translate_shader_log(log, pre.files));
  }
  return shader;
}

SceneShading current_shading = SceneShading::any;

// The label build_program gives a program built for a known scene shading.
std::string shading_label(SceneShading shading) { return std::string("oit scene shading: ") + to_string(shading); }

// Whether `source` includes the shading function, the one reader of OIT_SCENE_LIT.
bool shades(const PreprocessedShader& source) {
  return std::find(source.files.begin(), source.files.end(), "shaders/shading.glsl") != source.files.end();
}

// The caller's defines, then the current context's (shader_capabilities.h);
// stages that shade get the scene shading in force (SceneShadingScope),
// others not, so that a program that does not shade is one program for
// every scene.
std::vector<PreprocessedShader> preprocess_stages(const std::vector<ShaderStageSource>& stages,
                                                  const ShaderDefines& defines) {
  ShaderDefines all = defines;
  for (auto& define : capability_defines()) all.push_back(std::move(define));
  std::vector<PreprocessedShader> sources;
  for (const auto& stage : stages) {
    sources.push_back(preprocess_shader(stage.path, all));
    if (current_shading == SceneShading::any || !shades(sources.back())) continue;
    // After the #version line; the #line directive that follows keeps every
    // diagnostic's line number.
    std::string& text = sources.back().text;
    text.insert(text.find('\n') + 1,
                std::string("#define OIT_SCENE_LIT ") + (current_shading == SceneShading::lit ? "1" : "0") + "\n");
  }
  return sources;
}

// Every stage's type and full text (the defines are in it): equal keys,
// equal programs.
std::string cache_key(const std::vector<ShaderStageSource>& stages, const std::vector<PreprocessedShader>& sources) {
  std::string text;
  for (size_t i = 0; i < stages.size(); ++i)
    text += "stage " + std::to_string(stages[i].stage) + "\n" + sources[i].text + '\0';
  return ProgramCache::instance().key(text);
}

Program compile_or_load(const std::vector<ShaderStageSource>& stages, const std::vector<PreprocessedShader>& sources) {
  ProgramCache& cache = ProgramCache::instance();
  const std::string key = cache.enabled() ? cache_key(stages, sources) : "";
  if (!key.empty())
    if (std::optional<Program> program = cache.load(key)) return std::move(*program);

  std::vector<Shader> shaders;
  for (size_t i = 0; i < stages.size(); ++i) shaders.push_back(compile(stages[i], sources[i]));
  Program program(glCreateProgram());
  // Some drivers only keep a retrievable binary when told before linking.
  if (!key.empty()) glProgramParameteri(program.id(), GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
  for (const auto& shader : shaders) glAttachShader(program.id(), shader.id());
  glLinkProgram(program.id());
  GLint ok = GL_FALSE;
  glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = info_log(program.id(), glGetProgramiv, glGetProgramInfoLog);
    std::string names;
    for (const auto& stage : stages) names += (names.empty() ? "" : " + ") + stage.path;
    throw ShaderError("failed to link program (" + names + "):\n" + log);
  }
  for (const auto& shader : shaders) glDetachShader(program.id(), shader.id());
  cache.count_compiled();
  if (!key.empty()) cache.store(key, program);
  return program;
}

}  // namespace

PreprocessedShader preprocess_shader(const std::string& path, const ShaderDefines& defines) {
  return Preprocessor().run(path, defines);
}

std::string translate_shader_log(const std::string& log, const std::vector<std::string>& files) {
  // Mesa writes "0:12(5): error: ...", NVIDIA "0(12) : error ...".
  static const std::regex location_re(R"re((\d+):(\d+)\((\d+)\)|(\d+)\((\d+)\))re");
  std::string result;
  auto begin = std::sregex_iterator(log.begin(), log.end(), location_re);
  size_t last = 0;
  for (auto it = begin; it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    const bool mesa_form = m[1].matched;
    const size_t file = std::stoul(mesa_form ? m[1].str() : m[4].str());
    const std::string line = mesa_form ? m[2].str() : m[5].str();
    result += log.substr(last, static_cast<size_t>(m.position()) - last);
    result += (file < files.size() ? files[file] : "source " + std::to_string(file)) + ":" + line;
    last = static_cast<size_t>(m.position() + m.length());
  }
  result += log.substr(last);
  return result;
}

std::string program_cache_key(const std::vector<ShaderStageSource>& stages, const ShaderDefines& defines) {
  return cache_key(stages, preprocess_stages(stages, defines));
}

Program build_program(const std::vector<ShaderStageSource>& stages, const ShaderDefines& defines) {
  const std::vector<PreprocessedShader> sources = preprocess_stages(stages, defines);
  Program program = compile_or_load(stages, sources);
  if (current_shading != SceneShading::any && std::any_of(sources.begin(), sources.end(), shades)) {
    const std::string label = shading_label(current_shading);
    glObjectLabel(GL_PROGRAM, program.id(), GLsizei(label.size()), label.c_str());
  }
  return program;
}

const char* to_string(SceneShading shading) {
  switch (shading) {
    case SceneShading::unlit: return "unlit";
    case SceneShading::lit: return "lit";
    default: return "any";
  }
}

SceneShadingScope::SceneShadingScope(SceneShading shading) : outer_(current_shading) { current_shading = shading; }
SceneShadingScope::~SceneShadingScope() { current_shading = outer_; }
SceneShading current_scene_shading() { return current_shading; }

SceneShading scene_shading_of(GLuint program) {
  char label[64] = {};
  GLsizei length = 0;
  glGetObjectLabel(GL_PROGRAM, program, GLsizei(sizeof label), &length, label);
  const std::string text(label, size_t(length));
  for (SceneShading shading : {SceneShading::unlit, SceneShading::lit})
    if (text == shading_label(shading)) return shading;
  return SceneShading::any;
}

Program build_geometry_program(const std::string& fragment_path, const ShaderDefines& defines) {
  return build_program({{GL_VERTEX_SHADER, "shaders/geometry.vert"}, {GL_FRAGMENT_SHADER, fragment_path}}, defines);
}

Program build_fullscreen_program(const std::string& fragment_path, const ShaderDefines& defines) {
  return build_program({{GL_VERTEX_SHADER, "shaders/fullscreen.vert"}, {GL_FRAGMENT_SHADER, fragment_path}}, defines);
}

Program build_compute_program(const std::string& compute_path, const ShaderDefines& defines) {
  return build_program({{GL_COMPUTE_SHADER, compute_path}}, defines);
}

}  // namespace oit
