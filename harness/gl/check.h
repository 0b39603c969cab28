#pragma once
#include <source_location>
#include <stdexcept>
#include <string>

namespace oit {

// A GL error turned into an exception that names where it was detected.
class GlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws GlError if glGetError() reports anything; `what` says which step.
void gl_check(const std::string& what,
              std::source_location where = std::source_location::current());

// Empties GL's error queue, for a caller that has already turned a failure
// into an exception (or recovers from a refused call) so that no later
// gl_check blames an unrelated step.
void drain_gl_errors();

// Installs a KHR_debug callback that prints driver messages (debug builds).
void enable_gl_debug_output();

}  // namespace oit
