// core/huge_page_heap.h: small blocks allocated after advise_huge_pages_at_heap_top() land in
// memory the kernel may back with transparent huge pages, and the call leaves the heap's use as
// it found it. The tests set glibc's thresholds as prism's main() does, so they run in a child
// process (death tests, started afresh) to keep them out of the other tests' heap.

#include "core/huge_page_heap.h"

#include <gtest/gtest.h>
#include <malloc.h>

#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "tests/support/child_process.h"

namespace prism {
namespace {

using test::finish_child;

/// The kernel's THP mode: "always", "madvise" or "never" ("" when it cannot be read).
std::string thp_mode() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* mode : {"always", "madvise", "never"}) {
    if (text.find(std::string("[") + mode + "]") != std::string::npos) return mode;
  }
  return "";
}

/// The mappings of this process that /proc/self/smaps says may take huge pages.
struct EligibleRange {
  uintptr_t begin, end;
};
std::vector<EligibleRange> huge_page_eligible_mappings() {
  std::ifstream in("/proc/self/smaps");
  std::vector<EligibleRange> ranges;
  uintptr_t begin = 0, end = 0;
  for (std::string line; std::getline(in, line);) {
    uintptr_t a = 0, b = 0;
    if (std::sscanf(line.c_str(), "%" SCNxPTR "-%" SCNxPTR " ", &a, &b) == 2) {
      begin = a;
      end = b;
    } else if (line.rfind("THPeligible:", 0) == 0 && std::stoi(line.substr(12)) == 1) {
      ranges.push_back({begin, end});
    }
  }
  return ranges;
}

/// Allocates `count` blocks of 3 KiB (the size of OpenImageIO's string-table blocks), with or
/// without the advice first, and returns how many of them lie in huge-page-eligible memory.
int eligible_blocks_after(bool advised, int count) {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // as prism's main() sets them
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  const size_t in_use = mallinfo2().uordblks;
  if (advised) advise_huge_pages_at_heap_top(size_t{16} << 20);
  if (mallinfo2().uordblks != in_use) finish_child(false, "the advice left blocks allocated");
  std::vector<void*> blocks;
  for (int i = 0; i < count; ++i) blocks.push_back(std::malloc(3072));
  const std::vector<EligibleRange> ranges = huge_page_eligible_mappings();
  int eligible = 0;
  for (void* block : blocks) {
    for (const EligibleRange& r : ranges) {
      if (uintptr_t(block) >= r.begin && uintptr_t(block) < r.end) {
        ++eligible;
        break;
      }
    }
  }
  return eligible;
}

bool under_a_sanitizer() {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  return true;  // the sanitizers' allocators take neither glibc's thresholds nor its heap
#else
  return false;
#endif
}

TEST(CoreHugePageHeap, SmallBlocksAfterTheAdviceLandInHugePageEligibleMemory) {
  if (under_a_sanitizer()) GTEST_SKIP() << "a sanitizer's allocator replaces glibc's heap";
  if (thp_mode() != "madvise") {
    GTEST_SKIP() << "transparent huge pages are '" << thp_mode()
                 << "' here, not 'madvise': advice changes nothing to tell apart";
  }
  // In a process of its own (not a fork of this one): small blocks come from the heap's top
  // only when no freed block fits them, as at start-up, not after the tests run before.
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  // 4,000 blocks of 3 KiB are 12 MiB of the 16 advised: all but those before the first 2 MiB
  // boundary of the advised range (at most 2 MiB of them, 683 blocks) are in whole huge pages.
  const auto advised = [] {
    const int eligible = eligible_blocks_after(true, 4000);
    finish_child(eligible >= 3000,
                 std::to_string(eligible) + " of 4000 blocks in huge-page-eligible memory");
  };
  EXPECT_EXIT(advised(), ::testing::ExitedWithCode(0), "");
  // Without it, the heap is not eligible in "madvise" mode: what the test above tells apart.
  const auto unadvised = [] {
    const int eligible = eligible_blocks_after(false, 4000);
    finish_child(eligible < 3000,
                 std::to_string(eligible) + " of 4000 blocks eligible without the advice");
  };
  EXPECT_EXIT(unadvised(), ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace prism
