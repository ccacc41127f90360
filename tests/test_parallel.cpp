#include "osd_cull/error.h"
#include "osd_cull/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <vector>

namespace osd_cull {
namespace {

// Every item is visited exactly once, in contiguous chunks, whatever the count and threads.
TEST(ParallelChunks, VisitEveryItemOnceInContiguousChunks) {
  for (uint32_t n : {0u, 1u, 7u, 100u, 4097u}) {
    for (unsigned threads : {0u, 1u, 2u, 3u, 16u, 64u}) {
      std::vector<std::atomic<int>> seen(n);
      std::atomic<int> calls{0};
      parallelChunks(n, 1, threads, [&](uint32_t begin, uint32_t end) {
        ASSERT_LE(begin, end);
        ASSERT_LE(end, n);
        ++calls;
        for (uint32_t i = begin; i < end; ++i) ++seen[i];
      });
      for (uint32_t i = 0; i < n; ++i)
        ASSERT_EQ(seen[i].load(), 1) << n << " " << threads << " " << i;
      EXPECT_LE(calls.load(), 16) << "at most 16 threads";
      EXPECT_GE(calls.load(), 1);
    }
  }
}

// Below the minimum the calling thread does all of it in one call.
TEST(ParallelChunks, SmallCountsStayOnTheCallingThread) {
  int calls = 0;
  parallelChunks(999, 1000, 4, [&](uint32_t begin, uint32_t end) {
    ++calls;
    EXPECT_EQ(begin, 0u);
    EXPECT_EQ(end, 999u);
  });
  EXPECT_EQ(calls, 1);
}

// An exception in any chunk reaches the caller after all threads joined.
TEST(ParallelChunks, AnExceptionInAChunkReachesTheCaller) {
  std::atomic<int> finished{0};
  EXPECT_THROW(parallelChunks(1000, 1, 4,
                              [&](uint32_t begin, uint32_t) {
                                if (begin > 0) throw Error("chunk failed");
                                ++finished;
                              }),
               Error);
  EXPECT_EQ(finished.load(), 1);  // the first chunk ran to its end
}

// The huge-page vector holds n value-initialized elements (the advice changes nothing visible).
TEST(HugePageVector, HoldsValueInitializedElements) {
  const std::vector<double> big = hugePageVector<double>(size_t{3} << 20);  // 24 MB
  ASSERT_EQ(big.size(), size_t{3} << 20);
  size_t nonzero = 0;
  for (double v : big) nonzero += v != 0.0;
  EXPECT_EQ(nonzero, 0u);
  EXPECT_TRUE(hugePageVector<int>(0).empty());
  EXPECT_EQ(hugePageVector<int>(5), std::vector<int>(5, 0));
}

}  // namespace
}  // namespace osd_cull
