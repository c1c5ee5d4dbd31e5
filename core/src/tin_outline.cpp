// SPDX-License-Identifier: GPL-3.0-or-later
#include "tin_outline.h"

#include <algorithm>
#include <cstdint>

namespace tinlod {
namespace {

std::uint64_t mixed(std::uint64_t x) {  // splitmix64's finalizer
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace

// The triangles around an inner vertex close a fan: the vertices that follow it
// counter-clockwise in its triangles are those that precede it, the same set. On the
// outline the fan is open and one vertex more ends it each way, so the sums of a hash of
// each differ. That takes 8 bytes a vertex, where a map of the edges took about 50 an edge
// (a second or more and hundreds of MB for millions of triangles).
std::vector<bool> outlineVertices(const Tin& tin) {
  std::vector<std::uint64_t> balance(tin.vertices.size(), 0);
  for (const Triangle& t : tin.triangles)
    for (int k = 0; k < 3; ++k) balance[t[k]] += mixed(t[(k + 1) % 3]) - mixed(t[(k + 2) % 3]);
  std::vector<bool> outline(balance.size());
  for (std::size_t v = 0; v < balance.size(); ++v) outline[v] = balance[v] != 0;
  return outline;
}

std::size_t countOutlineVertices(const Tin& tin) {
  const std::vector<bool> outline = outlineVertices(tin);
  return static_cast<std::size_t>(std::count(outline.begin(), outline.end(), true));
}

}  // namespace tinlod
