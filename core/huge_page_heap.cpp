#include "core/huge_page_heap.h"

#include <sys/mman.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "core/huge_page_allocator.h"

namespace prism {

void advise_huge_pages_at_heap_top(size_t bytes) {
  std::vector<void*> blocks;
  uintptr_t begin = UINTPTR_MAX, end = 0;
  for (size_t covered = 0; covered < bytes;) {
    const size_t size = std::min(kHeapBlockBytes, bytes - covered);
    void* block = std::malloc(size);
    if (block == nullptr) break;
    blocks.push_back(block);
    begin = std::min(begin, uintptr_t(block));
    end = std::max(end, uintptr_t(block) + size);
    covered += size;
  }
  // Consecutive blocks from the top are contiguous: one range, advised once. (Each block after
  // the first already has its header written, in 4 KiB, which costs the huge page it falls in.)
  const uintptr_t first = (begin + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  const uintptr_t last = end / kHugePageBytes * kHugePageBytes;
  if (!blocks.empty() && last > first) {
    madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);  // advice only
  }
  for (auto block = blocks.rbegin(); block != blocks.rend(); ++block) std::free(*block);
}

}  // namespace prism
