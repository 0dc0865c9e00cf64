#include "core/huge_page_heap.h"

#include <sys/mman.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "core/huge_page_allocator.h"

namespace prism {

void advise_huge_pages_at_heap_top(size_t bytes) {
  bytes = std::min(bytes, kHeapBlockBytes);
  void* block = std::malloc(bytes);
  if (block == nullptr) return;
  const uintptr_t first = (uintptr_t(block) + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  const uintptr_t last = (uintptr_t(block) + bytes) / kHugePageBytes * kHugePageBytes;
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);  // advice
  std::free(block);
}

}  // namespace prism
