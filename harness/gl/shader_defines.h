#pragma once
// The #defines a program is built with: what build_program takes from its
// caller (shader_program.h) and what the current context adds
// (shader_capabilities.h). Its own header so that neither of those two
// includes the other for the type.
#include <string>
#include <utility>
#include <vector>

namespace oit {

// A #define injected after the #version line, e.g. {"K", "16"}.
using ShaderDefine = std::pair<std::string, std::string>;
using ShaderDefines = std::vector<ShaderDefine>;

}  // namespace oit
