#pragma once
// What a run that ran out of memory tells the user: at very large sizes a
// host allocation (std::bad_alloc) or a device allocation (GL_OUT_OF_MEMORY,
// an incomplete render target) fails, and the bare exception text names
// neither the size nor what to try.
#include <exception>
#include <string>

namespace oit {

// `failure`'s text, followed for a memory failure by the size, what ran out
// and what to try; other failures' text unchanged.
std::string explain_failure(const std::exception& failure, int width, int height);

}  // namespace oit
