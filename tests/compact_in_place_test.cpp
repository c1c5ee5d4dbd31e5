// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <numeric>
#include <random>
#include <vector>

#include "compact_in_place.h"

namespace tinlod {
namespace {

// Keeps each of `count` slots with probability `keep`, in a random new order.
Compaction randomCompaction(std::size_t count, double keep, std::mt19937& rng) {
  Compaction c;
  std::bernoulli_distribution kept(keep);
  for (std::size_t s = 0; s < count; ++s)
    if (kept(rng)) c.oldOf.push_back(static_cast<std::int32_t>(s));
  std::shuffle(c.oldOf.begin(), c.oldOf.end(), rng);
  c.newOf.assign(count, -1);
  for (std::size_t s = 0; s < c.oldOf.size(); ++s) c.newOf[c.oldOf[s]] = static_cast<std::int32_t>(s);
  return c;
}

struct Entry {
  std::uint64_t id;
  std::int32_t payload[5];
};

void expectGatherOf(const Compaction& c, std::size_t count) {
  std::vector<Entry> v(count);
  for (std::size_t s = 0; s < count; ++s) v[s] = {s, {int(s), -int(s), 7, 8, int(s % 13)}};
  const std::vector<Entry> old = v;
  compactInPlace(v, c);
  ASSERT_EQ(v.size(), c.oldOf.size());
  for (std::size_t s = 0; s < v.size(); ++s) {
    const Entry& want = old[c.oldOf[s]];
    ASSERT_EQ(v[s].id, want.id) << "slot " << s;
    ASSERT_TRUE(std::equal(v[s].payload, v[s].payload + 5, want.payload)) << "slot " << s;
  }
}

TEST(CompactInPlace, MovesEveryKeptEntryToItsNewSlotAsACopyWould) {
  std::mt19937 rng(12);
  for (const std::size_t count : {0u, 1u, 2u, 3u, 17u, 1000u, 100000u})
    for (const double keep : {0.0, 0.05, 0.5, 0.7, 0.95, 1.0}) {
      SCOPED_TRACE("count " + std::to_string(count) + ", keep " + std::to_string(keep));
      for (int trial = 0; trial < 4; ++trial) expectGatherOf(randomCompaction(count, keep, rng), count);
    }
}

// The simplifier's case: most slots keep their place or move a little, the dead ones
// are closed up, and some new slots form cycles among themselves.
TEST(CompactInPlace, HandlesFixedSlotsCyclesAndChainsTogether) {
  Compaction c;
  // Slot 0 stays, 1 and 2 swap, 3 is dropped, 4 -> 3, 5 -> 4, 6 dropped, 7 -> 5, 8 -> 7, 9 -> 6.
  c.oldOf = {0, 2, 1, 4, 5, 7, 9, 8};
  c.newOf = {0, 2, 1, -1, 3, 4, -1, 5, 7, 6};
  expectGatherOf(c, 10);
}

std::size_t residentBytes() {
  std::ifstream statm("/proc/self/statm");
  std::size_t size = 0, resident = 0;
  statm >> size >> resident;
  return resident * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

TEST(CompactInPlace, GivesBackThePagesPastTheNewEnd) {
  std::mt19937 rng(3);
  const std::size_t count = 8u << 20;  // 64 MB of entries
  std::vector<std::uint64_t> v(count);
  std::iota(v.begin(), v.end(), 0u);
  const Compaction c = randomCompaction(count, 0.25, rng);
  const std::size_t before = residentBytes();
  compactInPlace(v, c);
  const std::size_t after = residentBytes();
  EXPECT_EQ(v.capacity(), count);  // no copy was made
  // Three quarters of 64 MB went back, less the compaction's own bitmap (256 KB).
  EXPECT_GT(before, after + (40u << 20)) << "resident " << before << " bytes before, " << after << " after";
  for (std::size_t s = 0; s < v.size(); s += 4099) ASSERT_EQ(v[s], std::uint64_t(c.oldOf[s]));
}

}  // namespace
}  // namespace tinlod
