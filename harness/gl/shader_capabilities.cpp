#include "harness/gl/shader_capabilities.h"

#include <cstdlib>
#include <map>
#include <set>
#include <utility>

#include "harness/gl/gl.h"

namespace oit {
namespace {

// The current context's extensions, queried once per driver (renderer and
// version): a process normally has one context, the tests a few alike.
const std::set<std::string>& current_extensions() {
  static std::map<std::string, std::set<std::string>> by_driver;
  const auto text = [](GLenum name) {
    const auto* s = reinterpret_cast<const char*>(glGetString(name));
    return std::string(s ? s : "");
  };
  auto [it, inserted] = by_driver.try_emplace(text(GL_RENDERER) + "|" + text(GL_VERSION));
  if (inserted) {
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i) {
      if (const auto* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)))) it->second.insert(e);
    }
  }
  return it->second;
}

bool ballot_enabled() {
  const char* setting = std::getenv("OIT_SHADER_BALLOT");
  if (setting != nullptr && std::string(setting) == "off") return false;
  const std::set<std::string>& extensions = current_extensions();
  return extensions.count("GL_ARB_shader_ballot") > 0 && extensions.count("GL_ARB_gpu_shader_int64") > 0;
}

// Each ordered-access extension and the define that selects it, in order of preference.
const std::pair<const char*, const char*> kOrderedAccess[] = {
    {"GL_ARB_fragment_shader_interlock", "OIT_INTERLOCK_ARB"},
    {"GL_NV_fragment_shader_interlock", "OIT_INTERLOCK_NV"},
    {"GL_INTEL_fragment_shader_ordering", "OIT_ORDERING_INTEL"}};

}  // namespace

ShaderDefines capability_defines() {
  ShaderDefines defines;
  if (ballot_enabled()) defines.emplace_back("OIT_SHADER_BALLOT", "1");
  for (const auto& [extension, define] : kOrderedAccess) {
    if (current_extensions().count(extension) > 0) {
      defines.emplace_back(define, "1");
      break;
    }
  }
  return defines;
}

std::string ordered_access_extension() {
  for (const auto& [extension, define] : kOrderedAccess)
    if (current_extensions().count(extension) > 0) return extension;
  return "";
}

std::string atomics_path() { return ballot_enabled() ? "subgroup atomics" : "plain atomics"; }

}  // namespace oit
