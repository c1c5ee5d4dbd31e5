// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "tin_layers.h"
#include "tinlod/crs_transform.h"
#include "tinlod/dem.h"
#include "tinlod/feedback.h"
#include "tinlod/tin.h"

namespace tinlod {

// tinlod measures a TIN on the DEM's grid, each triangle linear in cell coordinates; read in
// the TIN's CRS, a triangle is linear there. Where that CRS is near-affine over a triangle
// (a projected DEM: exactly; a DEM in degrees away from the poles: within centimetres) the
// two agree. Near a pole, or across a DEM that wraps the globe, triangles turn over between
// the two, or their heights part: the figures would hold on the grid only.

// How many of the `count` triangles turn over between the grid and the TIN's CRS (those
// fewer of the two orientations). No PROJ: cheap over every triangle of every level.
std::size_t foldedTriangles(const std::vector<TinVertex>& vertices, std::size_t count, const TriangleAt& triangle);

// How far the TIN's CRS bends the DEM's grid: a bound of the norm of the map's second
// derivative, in the CRS's units per cell squared, so that |f(c + u) - f(c) - f'(c) u| is at
// most bound |u|^2 / 2. Twice the largest that second differences give on a 32 x 32 lattice
// over the DEM; infinite where PROJ cannot take the lattice, or where the samples change by
// more than half their largest from one to the next (too fast for a lattice to follow): 0 when
// the TIN's CRS is the DEM's.
double bendBound(const Dem& dem, const CrsTransform& toTin);

// How far a triangle's height at its centre in the CRS can be from that on the grid (the mean
// of its corners'), for a CRS whose bendBound is `bend`.
double heightGapBound(const TinVertex& a, const TinVertex& b, const TinVertex& c, double bend);

// The largest difference, in metres, between a triangle's height at its centre on the grid
// and in the TIN's CRS (the grid centre taken there with PROJ), over the triangles whose centre
// is on a valid cell and that PROJ can take: 0 when the TIN's CRS is the DEM's. A triangle that
// heightGapBound shows cannot part by more than `floor` is not measured (PROJ over a fine TIN's
// millions of centres cost 8.7 % of an insert), so a gap at or under `floor` is a lower bound.
struct HeightGap {
  double metres = 0;
  std::size_t measured = 0;  // the triangles measured with PROJ
};
HeightGap heightGap(const Dem& dem, const CrsTransform& toTin, const std::vector<TinVertex>& vertices, std::size_t count,
                    const TriangleAt& triangle, double floor);

// Refuses a TIN any of whose `turnCount` triangles turn over (Error, naming the fix); warns when
// the height gap of the `gapCount` triangles at `gapAt` (what `what` names, "level 14") exceeds a
// quarter of `maxError`, their largest error measured on the grid, and 1 cm.
void checkGridBend(const Dem& dem, const CrsTransform& toTin, const std::vector<TinVertex>& vertices, std::size_t turnCount,
                   const TriangleAt& turnAt, std::size_t gapCount, const TriangleAt& gapAt, double maxError,
                   const std::string& what, const ProgressRange& progress);

}  // namespace tinlod
