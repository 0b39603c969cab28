#pragma once
// Process-wide cache of linked GL programs as driver binaries
// (glGetProgramBinary / glProgramBinary, GL 4.1 core).
//
// Techniques build their programs in their constructors and the harness
// creates a technique per run, so without this cache a sweep compiles and
// links every program once per run. build_program (shader_program.h) keys
// the cache by the preprocessed text of every stage (defines included) and
// by GL_RENDERER + GL_VERSION, so one process compiles each (sources,
// defines) once per driver; every call still gets its own Program object,
// created from the stored binary. A binary the driver refuses (a driver
// update between store and load cannot happen within one process, but a
// driver may still reject it) is dropped and the program compiled again.
// Drivers that offer no binary format (GL_NUM_PROGRAM_BINARY_FORMATS = 0)
// compile every time.
//
// Not thread-safe: GL is driven from one thread, and so is this cache.
// OIT_PROGRAM_CACHE=off turns it off (every program compiled), e.g. to
// measure what it saves.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "harness/gl/handles.h"

namespace oit {

struct ProgramCacheStats {
  uint64_t compiled = 0;  // programs compiled and linked from source
  uint64_t reused = 0;    // programs created from a stored binary
};

class ProgramCache {
 public:
  static ProgramCache& instance();

  // False when OIT_PROGRAM_CACHE=off (read at every call).
  bool enabled() const;
  // The cache key of a program: the current context's renderer and version,
  // then `sources` (every stage's type and preprocessed text).
  std::string key(const std::string& sources) const;
  // A new program from the binary stored under `key`; nullopt when none is
  // stored or the driver refuses it (the entry is then dropped).
  std::optional<Program> load(const std::string& key);
  // Keeps the binary of a linked program; nothing when the driver offers no
  // binary format or returns an empty one.
  void store(const std::string& key, const Program& program);
  // Replaces a stored binary's bytes, keeping its format: for testing that a
  // binary the driver refuses falls back to compiling. False when `key` is
  // not stored.
  bool replace_binary_for_testing(const std::string& key, std::vector<uint8_t> bytes);
  void count_compiled() { ++stats_.compiled; }

  ProgramCacheStats stats() const { return stats_; }
  size_t size() const { return binaries_.size(); }
  void clear() { binaries_.clear(); }

 private:
  struct Binary {
    GLenum format = 0;
    std::vector<uint8_t> bytes;
  };
  std::map<std::string, Binary> binaries_;
  ProgramCacheStats stats_;
};

}  // namespace oit
