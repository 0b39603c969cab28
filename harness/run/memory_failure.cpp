#include "harness/run/memory_failure.h"

#include <cmath>
#include <new>

namespace oit {

std::string explain_failure(const std::exception& failure, int width, int height) {
  const std::string text = failure.what();
  const bool host = dynamic_cast<const std::bad_alloc*>(&failure) != nullptr;
  const bool device = text.find("GL_OUT_OF_MEMORY") != std::string::npos ||
                      text.find("is incomplete") != std::string::npos;
  if (!host && !device) return text;
  // One RGBA32F image (the render target, the reference, the read-back) at this size.
  const double image_mib = std::ceil(double(width) * double(height) * 16.0 / (1 << 20));
  return std::string("out of ") + (host ? "host" : "device") + " memory at " + std::to_string(width) + "x" +
         std::to_string(height) + ": " + (host ? "a host allocation failed (std::bad_alloc)" : text) +
         ". One RGBA32F image of this size is " + std::to_string(int64_t(image_mib)) +
         " MiB, the technique's buffers come on top. Try a smaller --size, or parameters that need less memory "
         "(a smaller k, fragment pool or bucket count)";
}

}  // namespace oit
