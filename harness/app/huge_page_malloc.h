#pragma once
// Transparent huge pages for the process's heap, which on software GL is
// where every GL buffer and texture lives.
//
// Why: Mesa llvmpipe allocates buffer storage with malloc. The linked-list
// resolve of 32 quads at 256x256 reads a 64 MiB node pool in an order that
// touches ~1000 distinct 4 KiB pages per 64x64 raster tile, which is more
// than the TLB holds: it measured 8.7 ms with 4 KiB pages and 6.6 ms with
// 2 MiB pages (llvmpipe, 2-core machine; results/reference/linked_list/README.md).
// Kernels configured with THP in "madvise" mode (Debian's default) give huge
// pages only to memory that asks for them, and glibc (2.35+) asks for its
// malloc memory when GLIBC_TUNABLES holds glibc.malloc.hugetlb=1, a setting
// read only at process start.
#include <string>

namespace oit {

// Re-executes the running program (/proc/self/exe, same arguments) with
// glibc.malloc.hugetlb=1 added to GLIBC_TUNABLES when that changes
// something: the kernel's THP mode is "madvise", the variable does not set
// the tunable already, and OIT_HUGE_PAGES is not "off". Returns normally
// when nothing is to be done or the exec fails (a warning on stderr then:
// the run goes on with 4 KiB pages, which host_page_policy() reports).
// Call first in main(), before any thread exists.
void relaunch_with_huge_page_malloc(char** argv);

// The page policy this process's heap runs under, for the CSV and `list`:
// "thp-always" (kernel), "thp-malloc" (madvise mode, glibc tunable set) or
// "4k" (THP never, unavailable, or madvise mode without the tunable).
std::string host_page_policy();

}  // namespace oit
