// SPDX-License-Identifier: GPL-3.0-or-later
// Private: a vertex's place, bit for bit, as a key: the tiles of a catalogue put a vertex
// of a line they share at the very same x and y.
#pragma once

#include <cstdint>
#include <cstring>
#include <functional>

#include "tinlod/tin.h"

namespace tinlod {

struct Place {
  std::uint64_t x, y;
  bool operator==(const Place& o) const { return x == o.x && y == o.y; }
};

struct PlaceHash {
  std::size_t operator()(const Place& p) const { return std::hash<std::uint64_t>()(p.x * 0x9E3779B97F4A7C15ull ^ p.y); }
};

inline Place placeOf(const TinVertex& v) {
  Place p;
  std::memcpy(&p.x, &v.x, sizeof p.x);
  std::memcpy(&p.y, &v.y, sizeof p.y);
  return p;
}

}  // namespace tinlod
