#include "core/memory.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstring>
#include <memory>
#include <vector>

namespace tandem {
namespace {

long minorFaults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
}

// A frame's worth of large temporaries, each written in full (as a pass fills its buffers);
// returns a checksum so that nothing is optimised away.
long allocateFrame(size_t blocks, size_t bytes) {
  std::vector<std::unique_ptr<char[]>> v;
  long sum = 0;
  for (size_t i = 0; i < blocks; ++i) {
    v.emplace_back(new char[bytes]);
    std::memset(v.back().get(), int(i + 1), bytes);
    for (size_t k = 0; k < bytes; k += 4096) sum += v.back()[k];
  }
  return sum;
}

// A frame reuses the last frame's memory: its pages are not faulted in again.
TEST(Memory, FreedBlocksAreReusedWithoutPageFaults) {
#if !defined(__GLIBC__) || defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "glibc's allocator only";
#else
  keepFreedMemoryForReuse();
  constexpr size_t kBlocks = 4, kBytes = 20u << 20;  // 80 MB, blocks below the 32 MB threshold
  const long pages = long(kBlocks * kBytes / 4096);
  // Two frames to settle the heap's layout (the second still faults one block in), then one
  // measured: glibc's defaults fault all of its pages in again every frame.
  for (int warm = 0; warm < 2; ++warm)
    EXPECT_EQ(allocateFrame(kBlocks, kBytes), 10 * pages / 4);  // 1 + 2 + 3 + 4 per page
  const long before = minorFaults();
  EXPECT_EQ(allocateFrame(kBlocks, kBytes), 10 * pages / 4);
  const long faults = minorFaults() - before;
  EXPECT_LT(faults, pages / 20) << "of " << pages << " pages";  // without it: every page
#endif
}

}  // namespace
}  // namespace tandem
