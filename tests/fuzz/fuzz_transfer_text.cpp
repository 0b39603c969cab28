// libFuzzer target: arbitrary bytes as a bucketed_kbuffer transfer-function
// text file, parsed both as a colour (1D) and as an opacity (2D) function.
// A parser may accept the bytes or reject them with std::invalid_argument;
// accepted bytes must give texels of the right count within their ranges.
// Anything else -- another exception, a crash, a sanitizer report, a hang or
// an allocation above -rss_limit_mb -- is a finding.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "algorithms/bucketed_kbuffer/transfer_files.h"

namespace {

void require(bool condition, const char* what) {
  if (!condition) {
    std::fprintf(stderr, "accepted input broke an invariant: %s\n", what);
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const std::vector<float> color = oit::bkb::parse_color_transfer_text(text, "fuzz.txt");
    require(color.size() == size_t(oit::bkb::kColorTransferSize) * 4, "colour texel count");
    for (float v : color) require(std::isfinite(v) && v >= 0.0f && v <= 255.0f, "colour multiplier in [0, 255]");
  } catch (const std::invalid_argument&) {
    // A clean rejection.
  }
  try {
    const std::vector<float> opacity = oit::bkb::parse_opacity_transfer_text(text, "fuzz.txt");
    require(opacity.size() == size_t(oit::bkb::kOpacityTransferSize) * oit::bkb::kOpacityTransferSize,
            "opacity texel count");
    for (float v : opacity) require(v >= 0.0f && v <= 1.0f, "opacity in [0, 1]");
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
