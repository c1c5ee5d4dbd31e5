// SPDX-License-Identifier: GPL-3.0-or-later
// Private: triangles ordered by their smallest vertex. Vertices are numbered along the
// TIN (row by row, or along a curve), so in this order the triangles of neighbouring
// stars lie side by side; the sampled TIN and the simplifier's mesh both keep it.
#pragma once

#include <cstdint>
#include <vector>

namespace tinlod {

// Slots renumbered: for each new slot its old one, and for each old slot its new one
// (-1 when dropped).
struct Compaction {
  std::vector<std::int32_t> oldOf, newOf;
};

// A stable counting sort of `count` triangles by the smallest of their vertices
// (numbered below `vertices`), as smallest(t) gives it, -1 for a triangle to drop.
// Writes into c and first, whose memory the caller may reuse from call to call.
template <class Smallest>
void orderBySmallestVertex(std::size_t count, std::size_t vertices, Smallest smallest, Compaction& c,
                           std::vector<std::int32_t>& first) {
  first.assign(vertices + 1, 0);
  for (std::size_t t = 0; t < count; ++t)
    if (smallest(t) >= 0) ++first[smallest(t) + 1];
  for (std::size_t v = 0; v < vertices; ++v) first[v + 1] += first[v];
  c.oldOf.resize(first.back());
  c.newOf.assign(count, -1);
  for (std::size_t t = 0; t < count; ++t)
    if (smallest(t) >= 0) {
      const std::int32_t slot = first[smallest(t)]++;
      c.newOf[t] = slot, c.oldOf[slot] = static_cast<std::int32_t>(t);
    }
}

}  // namespace tinlod
