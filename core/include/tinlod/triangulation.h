// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "tinlod/feedback.h"
#include "tinlod/tin.h"

namespace tinlod {

constexpr std::int32_t kNoNeighbour = -1;

// Triangles with their adjacency: neighbours[t][k] is the triangle across the edge
// opposite corner k of triangle t, or kNoNeighbour on the convex hull.
struct Triangulation {
  std::vector<Triangle> triangles;
  std::vector<std::array<std::int32_t, 3>> neighbours;
};

// The Delaunay triangulation (CGAL, exact predicates) of the vertices' x and y:
// counter-clockwise triangles of vertex indices. A vertex at exactly the x/y of an
// earlier one is left out of every triangle.
Triangulation delaunayTriangles(const std::vector<TinVertex>& vertices, const ProgressRange& progress);

}  // namespace tinlod
