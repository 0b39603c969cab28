// Helper of huge_page_malloc_test: starts like oitbench (relaunch first),
// then touches a 64 MiB malloc block, as llvmpipe does with a node pool, and
// prints what the process got: the reported policy, the GLIBC_TUNABLES it
// ended up with, and the kernel's count of its memory in huge pages.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include "harness/app/huge_page_malloc.h"

int main(int, char** argv) {
  oit::relaunch_with_huge_page_malloc(argv);
  constexpr size_t kBytes = size_t(64) << 20;
  auto* block = static_cast<char*>(std::malloc(kBytes));
  if (!block) return 1;
  std::memset(block, 1, kBytes);
  long anon_huge_kb = -1;
  std::ifstream rollup("/proc/self/smaps_rollup");
  for (std::string line; std::getline(rollup, line);) {
    if (line.rfind("AnonHugePages:", 0) == 0) anon_huge_kb = std::strtol(line.c_str() + 14, nullptr, 10);
  }
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  std::printf("policy=%s\nanon_huge_kb=%ld\ntunables=%s\nchecksum=%d\n", oit::host_page_policy().c_str(),
              anon_huge_kb, tunables ? tunables : "", int(block[kBytes / 2]));
  std::free(block);
  return 0;
}
