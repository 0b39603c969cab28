#include "harness/app/huge_page_malloc.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

namespace oit {
namespace {

constexpr const char* kTunable = "glibc.malloc.hugetlb=1";

// The bracketed word of /sys/kernel/mm/transparent_hugepage/enabled
// ("always [madvise] never"), or "" when the kernel has no THP.
std::string kernel_thp_mode() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  if (!std::getline(in, line)) return "";
  const auto open = line.find('['), close = line.find(']');
  if (open == std::string::npos || close == std::string::npos || close < open) return "";
  return line.substr(open + 1, close - open - 1);
}

bool tunable_requested() {
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  return tunables != nullptr && std::strstr(tunables, kTunable) != nullptr;
}

bool disabled_by_user() {
  const char* setting = std::getenv("OIT_HUGE_PAGES");
  return setting != nullptr && std::string(setting) == "off";
}

}  // namespace

void relaunch_with_huge_page_malloc(char** argv) {
#if defined(__GLIBC__) && defined(__linux__)
  if (disabled_by_user() || tunable_requested() || kernel_thp_mode() != "madvise") return;
  // The new image sees the tunable in its environment, so the check above
  // stops it from executing itself again.
  const char* existing_text = std::getenv("GLIBC_TUNABLES");
  const bool had_tunables = existing_text != nullptr;
  const std::string existing = had_tunables ? existing_text : "";
  const std::string tunables = existing.empty() ? kTunable : existing + ":" + kTunable;
  if (setenv("GLIBC_TUNABLES", tunables.c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);
  std::fprintf(stderr, "oitbench: warning: could not re-execute with huge-page malloc (%s); running with 4 KiB pages\n",
               std::strerror(errno));
  if (had_tunables) {
    setenv("GLIBC_TUNABLES", existing.c_str(), 1);
  } else {
    unsetenv("GLIBC_TUNABLES");
  }
#else
  (void)argv;
#endif
}

std::string host_page_policy() {
  const std::string mode = kernel_thp_mode();
  if (mode == "always") return "thp-always";
  if (mode == "madvise" && tunable_requested()) return "thp-malloc";
  return "4k";
}

}  // namespace oit
