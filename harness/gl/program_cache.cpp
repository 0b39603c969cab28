#include "harness/gl/program_cache.h"

#include <cstdlib>
#include <cstring>

#include "harness/gl/check.h"

namespace oit {
namespace {

std::string gl_string(GLenum name) {
  const auto* text = reinterpret_cast<const char*>(glGetString(name));
  return text ? text : "";
}

}  // namespace

ProgramCache& ProgramCache::instance() {
  static ProgramCache cache;
  return cache;
}

bool ProgramCache::enabled() const {
  const char* setting = std::getenv("OIT_PROGRAM_CACHE");
  return !(setting && std::strcmp(setting, "off") == 0);
}

std::string ProgramCache::key(const std::string& sources) const {
  // A binary is only valid for the driver that produced it.
  return gl_string(GL_RENDERER) + "\n" + gl_string(GL_VERSION) + "\n" + sources;
}

std::optional<Program> ProgramCache::load(const std::string& key) {
  auto it = binaries_.find(key);
  if (it == binaries_.end()) return std::nullopt;
  Program program(glCreateProgram());
  glProgramBinary(program.id(), it->second.format, it->second.bytes.data(),
                  static_cast<GLsizei>(it->second.bytes.size()));
  GLint ok = GL_FALSE;
  glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    // Refused (GL_INVALID_ENUM for an unknown format, or a failed link):
    // clear the error so no later gl_check blames the caller, and compile.
    drain_gl_errors();
    binaries_.erase(it);
    return std::nullopt;
  }
  ++stats_.reused;
  return program;
}

void ProgramCache::store(const std::string& key, const Program& program) {
  GLint formats = 0;
  glGetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &formats);
  if (formats <= 0) return;
  GLint length = 0;
  glGetProgramiv(program.id(), GL_PROGRAM_BINARY_LENGTH, &length);
  if (length <= 0) return;
  Binary binary;
  binary.bytes.resize(static_cast<size_t>(length));
  GLsizei written = 0;
  glGetProgramBinary(program.id(), length, &written, &binary.format, binary.bytes.data());
  if (written <= 0) return;
  binary.bytes.resize(static_cast<size_t>(written));
  binaries_[key] = std::move(binary);
}

bool ProgramCache::replace_binary_for_testing(const std::string& key, std::vector<uint8_t> bytes) {
  auto it = binaries_.find(key);
  if (it == binaries_.end()) return false;
  it->second.bytes = std::move(bytes);
  return true;
}

}  // namespace oit
