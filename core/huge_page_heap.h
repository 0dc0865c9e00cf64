#pragma once

// Transparent huge pages for the top of the calling thread's malloc heap, where a burst of small
// allocations is about to land (core/huge_page_allocator.h does the same for single big arrays).

#include <cstddef>

namespace prism {

/// Advises the next `bytes` of the calling thread's malloc heap as transparent huge pages
/// (madvise(MADV_HUGEPAGE)), so that many small blocks allocated there next fault in 2 MiB at a
/// time instead of 4 KiB at a time: OpenImageIO's static initialisers make ~8,500 blocks of
/// 2-4 KiB (its string table), 25 MiB that cost ~7,000 page faults at ~12 us each on the
/// virtual machines prism is measured on, against 12 huge-page faults of ~0.1-0.4 ms.
///
/// How: one block of `bytes` (at most kHeapBlockBytes) is allocated, the whole 2 MiB-aligned
/// pages inside it advised, and the block freed back to the heap's top, from which glibc carves
/// the next allocations in order. That needs the block to come from the heap
/// (below M_MMAP_THRESHOLD) and the top to stay (M_TRIM_THRESHOLD), as prism's main() sets them,
/// and the next blocks to come from the top, as they do while the heap has no freed block that
/// fits them: at start-up, and in the fresh heap of a thread that has not allocated much. Where
/// any of that does not hold, or THP is off, only speed changes. Nothing is touched: pages the
/// thread never uses cost nothing.
void advise_huge_pages_at_heap_top(size_t bytes);

/// The most advise_huge_pages_at_heap_top() advises (its one block): below the 32 MiB from which
/// main() lets glibc map blocks of their own.
inline constexpr size_t kHeapBlockBytes = size_t{31} << 20;

}  // namespace prism
