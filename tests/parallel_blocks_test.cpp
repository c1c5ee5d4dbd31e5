// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>
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

TEST(ParallelBlocks, ThisThreadAloneKeepsTheWorkOnTheCallingThread) {
  const unsigned usual = threadCount();
  std::vector<std::thread::id> workers(100000);
  {
    const ThisThreadAlone alone;
    EXPECT_EQ(threadCount(), 1u);
    forEachBlock(static_cast<int>(workers.size()), [&](int begin, int end) {
      for (int i = begin; i < end; ++i) workers[i] = std::this_thread::get_id();
    }, {});
    for (const std::thread::id& id : workers) ASSERT_EQ(id, std::this_thread::get_id());
    // Other threads keep the usual count.
    unsigned elsewhere = 0;
    std::thread([&] { elsewhere = threadCount(); }).join();
    EXPECT_EQ(elsewhere, usual);
  }
  EXPECT_EQ(threadCount(), usual);
}

}  // namespace
}  // namespace tinlod
