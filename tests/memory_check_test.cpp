// SPDX-License-Identifier: GPL-3.0-or-later
// The check of a DEM against the machine's memory, on given figures.
#include <gtest/gtest.h>

#include "test_support.h"
#include "tinlod/error.h"
#include "tinlod/memory_check.h"

namespace tinlod {
namespace {

const MemoryUse kUse{"building its hierarchy", 50, "cut it into tiles"};

TEST(MemoryCheck, TooLargeOnlyWhenThreeQuartersOfTheEstimateExceedTheMachine) {
  const MachineMemory m{16e9, 8e9};
  EXPECT_EQ(memoryVerdict(4e9, m), MemoryVerdict::Fits);
  EXPECT_EQ(memoryVerdict(8e9, m), MemoryVerdict::Fits);  // all that is available, not more
  EXPECT_EQ(memoryVerdict(8.1e9, m), MemoryVerdict::Tight);
  EXPECT_EQ(memoryVerdict(21.3e9, m), MemoryVerdict::Tight);  // 3/4 of it is 15.98 GB
  EXPECT_EQ(memoryVerdict(21.4e9, m), MemoryVerdict::TooLarge);
  // Unknown figures refuse nothing.
  EXPECT_EQ(memoryVerdict(1e15, MachineMemory{}), MemoryVerdict::Fits);
}

TEST(MemoryCheck, TheMessagesGiveTheCellsTheEstimateTheMachineAndTheFix) {
  test::RecordingFeedback fb;
  const ProgressRange range(fb.feedback(), 0, 1);
  // 20,000 x 10,000 cells at 50 bytes: 10 GB.
  checkMemory("dem.tif", 20000, 10000, kUse, range, {64e9, 32e9});
  EXPECT_TRUE(fb.warnings.empty());
  checkMemory("dem.tif", 20000, 10000, kUse, range, {16e9, 8e9});
  ASSERT_EQ(fb.warnings.size(), 1u);
  EXPECT_EQ(fb.warnings[0], "'dem.tif' has 200000000 cells (20000 x 10000): building its hierarchy holds about 10 GB for "
                            "them (50 bytes a cell), more than the 8 GB of memory free now: the run may be slow, or "
                            "stopped by the system; cut it into tiles");
  EXPECT_EQ(test::errorOf([&] { checkMemory("dem.tif", 20000, 10000, kUse, range, {7e9, 6e9}); }),
            "'dem.tif' has 200000000 cells (20000 x 10000): building its hierarchy holds about 10 GB for them (50 bytes "
            "a cell), more than the 7 GB of memory and swap this run may use: cut it into tiles");
}

// Where even the DEM's own cells do not fit, a larger -block cannot help: not offered.
TEST(MemoryCheck, ALargerBlockIsOfferedOnlyWhereItCouldFit) {
  const MemoryUse use{"building its hierarchy", 57, "tiles, or a larger -block", 13, "tiles"};
  const auto said = [&](std::int64_t side) {
    return test::errorOf([&] { checkMemory("d.tif", side, side, use, ProgressRange(Feedback{}, 0, 1), {16e9, 8e9}); });
  };
  EXPECT_NE(said(20000).find("this run may use: tiles, or a larger -block"), std::string::npos) << said(20000);
  EXPECT_NE(said(60000).find("this run may use: tiles"), std::string::npos) << said(60000);
  EXPECT_EQ(said(60000).find("-block"), std::string::npos) << said(60000);
}

TEST(MemoryCheck, ThisMachinesMemoryIsRead) {
  const MachineMemory m = machineMemory();
  EXPECT_GT(m.total, 100e6);
  EXPECT_GT(m.available, 0);
  EXPECT_LE(m.available, m.total);
}

}  // namespace
}  // namespace tinlod
