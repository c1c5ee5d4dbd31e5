// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

#include "parallel_blocks.h"

namespace tinlod {
namespace {

TEST(ParallelBlocks, EveryItemOnceInBlocks) {
  std::vector<std::atomic<int>> seen(100000);
  forEachBlock(static_cast<int>(seen.size()), [&](int begin, int end) {
    for (int i = begin; i < end; ++i) ++seen[i];
  }, {});
  for (const auto& s : seen) ASSERT_EQ(s.load(), 1);
}

TEST(ParallelBlocks, RunBothRunsBothAndRethrowsEitherFailureAfterBoth) {
  std::atomic<int> ran{0};
  runBoth([&] { ++ran; }, [&] { ++ran; });
  EXPECT_EQ(ran.load(), 2);
  ran = 0;
  EXPECT_THROW(runBoth([&] { ++ran; }, [&] { ++ran, throw std::runtime_error("second"); }), std::runtime_error);
  EXPECT_EQ(ran.load(), 2);
  ran = 0;
  EXPECT_THROW(runBoth([&] { ++ran, throw std::runtime_error("first"); }, [&] { ++ran; }), std::runtime_error);
  EXPECT_EQ(ran.load(), 2);  // the second was waited for, not left running
}

}  // namespace
}  // namespace tinlod
