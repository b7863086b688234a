/* Large arrays on transparent huge pages. Where the kernel gives huge pages on request only
 * (transparent_hugepage "madvise", Debian's default), an array of a few megabytes and more is
 * marked MADV_HUGEPAGE as soon as it is allocated, before its first touch: its pages are then
 * faulted in 2 MB at a time instead of 4 kB, and its loops miss the TLB less. The set-up writes
 * hundreds of megabytes of bond rows once, and first-touch faults had taken a quarter of its time
 * (perf, the fragmenting cylinder's 14.7 million bonds on a virtual machine). Where huge pages are
 * always or never given, or the call fails, nothing changes: it is advice, and the values are the
 * same bits either way. glibc's own switch (GLIBC_TUNABLES=glibc.malloc.hugetlb=1) does the same
 * for every allocation, but is read from the environment at start only. */
#if defined(__linux__)
#define _DEFAULT_SOURCE /* (MADV_HUGEPAGE, beside the project's _POSIX_C_SOURCE) */
#endif
#include "core/core.h"

#include <stdint.h>
#if defined(__linux__)
#include <sys/mman.h>
#endif

enum { PF_HUGE_PAGE = 2 << 20, PF_HUGE_MIN = 4 << 20 };

void pf_memory_huge_pages(void *p, size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (!p || bytes < PF_HUGE_MIN) return;
  const uintptr_t lo = ((uintptr_t)p + PF_HUGE_PAGE - 1) & ~(uintptr_t)(PF_HUGE_PAGE - 1);
  const uintptr_t hi = ((uintptr_t)p + bytes) & ~(uintptr_t)(PF_HUGE_PAGE - 1);
  if (hi > lo) (void)madvise((void *)lo, hi - lo, MADV_HUGEPAGE);
#else
  (void)p, (void)bytes;
#endif
}
