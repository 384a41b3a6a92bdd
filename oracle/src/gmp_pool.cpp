#include "pge/oracle_exact.hpp"

#include <gmp.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace pge::oracle {

#if !defined(__SANITIZE_ADDRESS__)  // kept blocks would hide a use after free from AddressSanitizer
namespace {

// Blocks of 1 to kClasses limbs, each class an exact size: a block GMP gives back with size n
// is handed out again only for size n. Every block comes from std::malloc, so a block that was
// allocated before the pool was installed (by GMP's default functions, malloc too) may be kept
// and handed out, and one the pool handed out may be released by free() as well.
constexpr std::size_t kLimb = sizeof(mp_limb_t);
constexpr std::size_t kClasses = 16;
constexpr unsigned kKeptPerClass = 1u << 14;  // at most 2 MiB kept per class, per thread

struct FreeBlock {
  FreeBlock* next;
};
static_assert(sizeof(FreeBlock) <= kLimb);

// Per thread, zero-initialised and trivially destructible (no guard on access). A thread that
// ends leaves its kept blocks behind, bounded by kKeptPerClass; the oracle runs in one thread.
thread_local FreeBlock* kept[kClasses + 1];
thread_local unsigned kept_count[kClasses + 1];

std::size_t class_of(std::size_t bytes) {  // 0: not pooled
  return bytes % kLimb == 0 && bytes / kLimb <= kClasses ? bytes / kLimb : 0;
}

[[noreturn]] void out_of_memory(std::size_t bytes) {
  std::fprintf(stderr, "pge: cannot allocate %zu bytes for an exact number\n", bytes);
  std::abort();  // as GMP's own allocator does: its functions cannot report a failure
}

void* raw_allocate(std::size_t bytes) {
  void* p = std::malloc(bytes);
  if (p == nullptr) out_of_memory(bytes);
  return p;
}

void* pooled_allocate(std::size_t bytes) {
  const std::size_t c = class_of(bytes);
  if (c != 0 && kept[c] != nullptr) {
    FreeBlock* b = kept[c];
    kept[c] = b->next;
    --kept_count[c];
    return b;
  }
  return raw_allocate(bytes);
}

void pooled_free(void* p, std::size_t bytes) {
  const std::size_t c = class_of(bytes);
  if (c == 0 || kept_count[c] >= kKeptPerClass) {
    std::free(p);
    return;
  }
  auto* b = static_cast<FreeBlock*>(p);
  b->next = kept[c];
  kept[c] = b;
  ++kept_count[c];
}

void* pooled_reallocate(void* p, std::size_t old_bytes, std::size_t new_bytes) {
  if (class_of(old_bytes) == 0 || class_of(new_bytes) == 0) {
    void* q = std::realloc(p, new_bytes);
    if (q == nullptr) out_of_memory(new_bytes);
    return q;
  }
  if (old_bytes == new_bytes) return p;
  void* q = pooled_allocate(new_bytes);
  std::memcpy(q, p, old_bytes < new_bytes ? old_bytes : new_bytes);
  pooled_free(p, old_bytes);
  return q;
}

}  // namespace

bool use_pooled_gmp_allocation() {
  mp_set_memory_functions(pooled_allocate, pooled_reallocate, pooled_free);
  return true;
}
#else
bool use_pooled_gmp_allocation() { return false; }
#endif

}  // namespace pge::oracle
