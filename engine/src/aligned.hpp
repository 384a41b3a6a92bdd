// An allocator for the world's large arrays: storage starts on a 64-byte boundary (a cache line
// on the x86-64 and ARM machines PGE runs on), for arrays laid out in cache-line groups, and an
// array of 2 MiB or more starts on a 2 MiB boundary and is offered to Linux's transparent huge
// pages (madvise MADV_HUGEPAGE; many systems, Debian's default among them, give huge pages only
// to memory that asks). With 1e5 bodies the bodies and queues take about 70 MB: in 4 KiB pages
// nearly every access to another body also misses the TLB; in 2 MiB pages the mappings fit.
// Measured on the gas at 1e5 (2-core Xeon VM): about 5% less time per event.
// Elsewhere, or if the kernel declines, the memory is ordinary.
// Also prefetch_line, the one place that asks the processor for a line ahead of its use.
#pragma once

#include <cstddef>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace pge {

template <class U> struct CacheAligned {
  using value_type = U;
  static constexpr std::size_t kLine = 64;
  static constexpr std::size_t kHugePage = std::size_t{2} << 20;
  CacheAligned() = default;
  template <class V> CacheAligned(const CacheAligned<V>&) {}  // NOLINT: rebinding
  static std::size_t alignment(std::size_t bytes) { return bytes >= kHugePage ? kHugePage : kLine; }
  U* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(U);
    void* p = ::operator new(bytes, std::align_val_t{alignment(bytes)});
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (bytes >= kHugePage) madvise(p, bytes / kHugePage * kHugePage, MADV_HUGEPAGE);  // a hint: failure is harmless
#endif
    return static_cast<U*>(p);
  }
  void deallocate(U* p, std::size_t n) { ::operator delete(p, std::align_val_t{alignment(n * sizeof(U))}); }
  template <class V> bool operator==(const CacheAligned<V>&) const { return true; }
};

// Starts fetching the cache line holding p (a hint; nothing where the compiler has no builtin).
// On x86-64 an asm statement: GCC treats __builtin_prefetch as free of side effects, so a loop
// that only prefetches (visit_next's, prefetch_around's) is deleted as an empty loop under
// C++'s forward-progress rule (-ffinite-loops): the World<double> of 62d1855 had no prefetch
// left in step() at all. `volatile` keeps every request where it is written.
inline void prefetch_line(const void* p) {
#if defined(__GNUC__) && defined(__x86_64__)
  asm volatile("prefetcht0 %0" : : "m"(*static_cast<const char*>(p)));
#elif defined(__GNUC__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}

}  // namespace pge
