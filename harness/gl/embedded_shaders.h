#pragma once
#include <map>
#include <string>

namespace oit {
// GLSL sources compiled into the binary, keyed by path relative to the
// source root (e.g. "shaders/shading.glsl"). Generated at build time.
const std::map<std::string, std::string, std::less<>>& embedded_shader_sources();
}  // namespace oit
