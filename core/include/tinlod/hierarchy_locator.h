// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstdint>
#include <limits>
#include <memory>

#include "tinlod/hierarchy.h"

namespace tinlod {

// Where a query point fell: the triangle (an index into Hierarchy::triangles) and the
// height of its plane there; no triangle for a point outside the TIN or in a hole.
struct LocatedPoint {
  std::int64_t triangle = -1;
  double z = std::numeric_limits<double>::quiet_NaN();
  bool found() const { return triangle >= 0; }
};

// How far beyond the raster's edge a point is still located, as a share of a DEM cell
// (HierarchyLocator::reach); the simplifier cuts a raster edge inside by no more
// (OutlineChain), so that every edge cell's centre stays within it.
constexpr double kRasterEdgeReach = 0.05;

// Kirkpatrick's point location: the containing triangle at the coarsest level, from a
// bucket grid, then among the finer triangles it replaced, level by level, down to the
// level asked for: O(log n) per point. Triangles are closed, so a point on an edge or a
// vertex is found; it takes the first containing triangle in a fixed order, so the
// answer is deterministic. A point beyond the raster's edge by at most reach() (5 % of a
// DEM cell) takes a triangle with an edge along the raster's that near, nearest first, and
// the height of its plane: the edge cells' centres of a DEM in degrees lie on curves in the
// TIN's CRS, just outside the straight edges between its vertices. Not beside a hole. The hierarchy must outlive the locator, which keeps a
// reference to it. locate() is const and keeps no state: threads may share a locator.
// Construction takes a fraction of a second and about 24 bytes per triangle of the
// hierarchy (a copy of each star packed for the search); it throws Error when the
// hierarchy is inconsistent (a star's triangles not a fan around its vertex).
class HierarchyLocator {
 public:
  explicit HierarchyLocator(const Hierarchy& h);
  ~HierarchyLocator();
  HierarchyLocator(HierarchyLocator&&) noexcept;
  HierarchyLocator& operator=(HierarchyLocator&&) noexcept;

  // Throws Error for a level outside 0 .. h.coarsest().
  LocatedPoint locate(double x, double y, int level = 0) const;
  // How far off the TIN a point is still located, in the TIN's CRS units.
  double reach() const;

 private:
  struct Impl;
  std::unique_ptr<const Impl> impl_;
};

}  // namespace tinlod
