// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <vector>

#include "tinlod/feedback.h"
#include "tinlod/tin.h"

namespace tinlod {

// The Delaunay triangulation (CGAL, exact predicates) of the vertices' x and y:
// counter-clockwise triangles of vertex indices. A vertex at exactly the x/y of an
// earlier one is left out of every triangle.
std::vector<Triangle> delaunayTriangles(const std::vector<TinVertex>& vertices,
                                        const ProgressRange& progress);

}  // namespace tinlod
