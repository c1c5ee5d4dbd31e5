// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>

#include "tinlod/dem.h"
#include "tinlod/feedback.h"
#include "tinlod/tin.h"
#include "tinlod/triangulation.h"

namespace tinlod {

// Sets tin.triangles to the triangles of `triangulation` (of tin.vertices, sampled
// from `dem`) that lie on valid data:
// - a triangle whose closed footprint in the DEM grid (its vertices' cell centres)
//   contains the centre of a missing cell would bridge a nodata hole: it goes;
// - a triangle whose cells are collinear in the grid covers no cell; where it is on
//   the TIN's boundary it is a sliver the jitter made along a straight edge: peeled
//   off, as are the slivers that its removal exposes.
// Then drops vertices left in no triangle and renumbers the rest. Returns the number
// of vertices dropped.
std::size_t keepTrianglesOnValidData(const Dem& dem, const Triangulation& triangulation, Tin& tin,
                                     const ProgressRange& progress);

// The same choice of triangles, returned as they are (indexing tin.vertices, which only
// give the triangles' cells); nothing is renumbered. With `neighbours`, each kept
// triangle's neighbours too, as keepTrianglesOnValidData sets them (numbered as the kept
// triangles, kNoNeighbour across an outline edge).
std::vector<Triangle> trianglesOnValidData(const Dem& dem, const Triangulation& triangulation, const Tin& tin,
                                           std::vector<std::array<std::int32_t, 3>>* neighbours = nullptr,
                                           const ProgressRange& progress = ProgressRange(Feedback{}, 0, 1));

}  // namespace tinlod
