// SPDX-License-Identifier: GPL-3.0-or-later
// Private: a stable least-significant-digit radix sort on 64-bit keys. The simplifier
// sorts every level's candidates by importance; on half a million pairs this is a few
// passes over memory where a comparison sort took four times as long.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

namespace tinlod {

// Bits of a double that sort as the double does (negative values included).
inline std::uint64_t orderedBits(double value) {
  if (value == 0) value = 0;  // -0 sorts with 0, as it compares
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits >> 63 ? ~bits : bits | (std::uint64_t{1} << 63);
}

// Sorts items by key(item), ascending; items with equal keys keep their order. `scratch`
// is the caller's, so that repeated sorts reuse its memory. A digit that every key
// shares costs no pass.
template <class T, class Key>
void radixSort(std::vector<T>& items, Key key, std::vector<T>& scratch) {
  constexpr int kBits = 11, kDigits = (64 + kBits - 1) / kBits;
  constexpr std::size_t kBuckets = std::size_t{1} << kBits;
  std::vector<std::array<std::size_t, kBuckets>> counts(kDigits);
  for (auto& c : counts) c.fill(0);
  for (const T& item : items) {
    const std::uint64_t k = key(item);
    for (int d = 0; d < kDigits; ++d) ++counts[d][(k >> (d * kBits)) & (kBuckets - 1)];
  }
  scratch.resize(items.size());
  for (int d = 0; d < kDigits; ++d) {
    std::array<std::size_t, kBuckets>& c = counts[d];
    if (items.empty() || c[(key(items.front()) >> (d * kBits)) & (kBuckets - 1)] == items.size()) continue;
    std::size_t sum = 0;
    for (std::size_t& n : c) {
      const std::size_t here = n;
      n = sum, sum += here;
    }
    for (const T& item : items) scratch[c[(key(item) >> (d * kBits)) & (kBuckets - 1)]++] = item;
    items.swap(scratch);
  }
}

}  // namespace tinlod
