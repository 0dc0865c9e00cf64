#pragma once

// An allocator for the few big arrays of a render: the film's exact sums (192 bytes a pixel),
// the pixels of the images it resolves to (core/film.h, core/image.h), and the wide BVH's nodes
// and triangle blocks (accel/bvh/wide_bvh.h).

#include <sys/mman.h>

#include <cstddef>
#include <cstdlib>
#include <limits>
#include <memory>
#include <new>

namespace prism {

/// Bytes of a transparent huge page on x86-64.
inline constexpr size_t kHugePageBytes = size_t{2} << 20;

/// std::allocator, except that arrays of at least kHugePageBytes are aligned to 2 MiB and
/// advised to the kernel as transparent huge pages (madvise(MADV_HUGEPAGE); "madvise" is
/// Debian's default THP mode). Touching fresh memory costs a page fault per page: per 4 KiB
/// that is ~8,000 faults for a 480 x 360 film, which on the virtual machines prism is measured
/// on cost ~14 us each (0.1 s of a 4.5 s render); per 2 MiB it is 17. Where THP is off the
/// advice is ignored and nothing else changes. Stateless: any two instances are equal.
template <typename T>
struct HugePageAllocator {
  using value_type = T;

  HugePageAllocator() noexcept = default;
  template <typename U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  T* allocate(size_t n) {
    if (n > std::numeric_limits<size_t>::max() / sizeof(T)) throw std::bad_array_new_length();
    const size_t bytes = n * sizeof(T);
    if (bytes < kHugePageBytes) return std::allocator<T>().allocate(n);
    const size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    void* p = std::aligned_alloc(kHugePageBytes, rounded);
    if (p == nullptr) throw std::bad_alloc();
    madvise(p, rounded, MADV_HUGEPAGE);  // advice: its failure changes nothing but speed
    return static_cast<T*>(p);
  }

  void deallocate(T* p, size_t n) noexcept {
    if (n * sizeof(T) < kHugePageBytes) {
      std::allocator<T>().deallocate(p, n);
    } else {
      std::free(p);
    }
  }

  template <typename U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
};

}  // namespace prism
