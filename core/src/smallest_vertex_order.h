// SPDX-License-Identifier: GPL-3.0-or-later
// Private: triangles ordered by their smallest vertex. Vertices are numbered along the
// TIN (row by row, or along a curve), so in this order the triangles of neighbouring
// stars lie side by side; the sampled TIN and the simplifier's mesh both keep it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "parallel_blocks.h"

namespace tinlod {

// Slots renumbered: for each new slot its old one, and for each old slot its new one
// (-1 when dropped).
struct Compaction {
  std::vector<std::int32_t> oldOf, newOf;
};

// The counting sort's tallies by vertex, one array for each half of the triangles; a
// caller may keep them from call to call to reuse their memory.
using VertexTallies = std::array<std::vector<std::int32_t>, 2>;

// A stable counting sort of `count` triangles by the smallest of their vertices
// (numbered below `vertices`), as smallest(t) gives it, -1 for a triangle to drop.
// Each half of the triangles is counted and placed on a core of its own; among equal
// keys the first half's go first, so the order is that of one serial stable sort.
// Writes into c and tallies, whose memory the caller may reuse from call to call.
template <class Smallest>
void orderBySmallestVertex(std::size_t count, std::size_t vertices, Smallest smallest, Compaction& c,
                           VertexTallies& tallies) {
  const std::size_t bounds[3] = {0, count / 2, count};
  auto tally = [&](int h) {
    std::vector<std::int32_t>& n = tallies[h];
    n.assign(vertices, 0);
    for (std::size_t t = bounds[h]; t < bounds[h + 1]; ++t)
      if (const std::int32_t v = smallest(t); v >= 0) ++n[v];
  };
  runBoth([&] { tally(0); }, [&] { tally(1); });
  std::int32_t next = 0;  // tallies become where each half's triangles of a vertex start
  for (std::size_t v = 0; v < vertices; ++v)
    for (std::vector<std::int32_t>& n : tallies) {
      const std::int32_t here = n[v];
      n[v] = next, next += here;
    }
  c.oldOf.resize(static_cast<std::size_t>(next));
  c.newOf.resize(count);
  auto place = [&](int h) {
    std::vector<std::int32_t>& at = tallies[h];
    for (std::size_t t = bounds[h]; t < bounds[h + 1]; ++t) {
      const std::int32_t v = smallest(t);
      const std::int32_t slot = v < 0 ? -1 : at[v]++;
      c.newOf[t] = slot;
      if (slot >= 0) c.oldOf[slot] = static_cast<std::int32_t>(t);
    }
  };
  runBoth([&] { place(0); }, [&] { place(1); });
}

}  // namespace tinlod
