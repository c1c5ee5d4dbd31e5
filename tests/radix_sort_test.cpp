// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "radix_sort.h"

namespace tinlod {
namespace {

using Item = std::pair<double, std::uint32_t>;

// The simplifier's order: by value, then by position in the input (the radix sort is
// stable), which is what std::stable_sort gives.
void expectSortedLikeStableSort(std::vector<Item> items) {
  std::vector<Item> expected = items;
  std::stable_sort(expected.begin(), expected.end(), [](const Item& a, const Item& b) { return a.first < b.first; });
  std::vector<Item> scratch;
  radixSort(items, [](const Item& i) { return orderedBits(i.first); }, scratch);
  ASSERT_EQ(items.size(), expected.size());
  for (std::size_t i = 0; i < items.size(); ++i) {
    EXPECT_EQ(items[i].second, expected[i].second) << "at " << i;
    if (items[i].second != expected[i].second) return;
  }
}

TEST(RadixSort, OrdersLikeAStableSortOnRandomValuesWithTies) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1e6, 1e6);
  std::uniform_int_distribution<int> pick(0, 9);
  std::vector<Item> items;
  for (std::uint32_t i = 0; i < 20000; ++i) {
    double v = u(rng);
    if (pick(rng) == 0) v = 0;  // many ties, as flat terrain gives
    if (pick(rng) == 1) v = 1e-300 * (pick(rng) - 5);
    items.push_back({v, i});
  }
  expectSortedLikeStableSort(items);
}

TEST(RadixSort, SignedZerosInfinitiesAndOneValue) {
  const double inf = std::numeric_limits<double>::infinity();
  expectSortedLikeStableSort({{0.0, 0}, {-0.0, 1}, {inf, 2}, {-inf, 3}, {-0.0, 4}, {1.5, 5}, {-1.5, 6}, {0.0, 7}});
  std::vector<Item> same;
  for (std::uint32_t i = 0; i < 1000; ++i) same.push_back({2.0, i});
  expectSortedLikeStableSort(same);  // every digit shared: no pass at all, the order kept
  expectSortedLikeStableSort({});
}

}  // namespace
}  // namespace tinlod
