// SPDX-License-Identifier: GPL-3.0-or-later
#include "grid_bend.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "text_and_paths.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

// A vertex's place on the grid, in cells (its jitter included).
double gridCol(const TinVertex& v) { return v.col + 0.5 + double(v.dcol); }
double gridRow(const TinVertex& v) { return v.row + 0.5 + double(v.drow); }

double cross(double ax, double ay, double bx, double by, double cx, double cy) {
  return (bx - ax) * (cy - ay) - (cx - ax) * (by - ay);
}

// Twice the area over the longest side squared: about 1.7 for an equilateral triangle, near 0
// for a sliver, whose orientation the slightest bend may turn (2 slivers along vancouver's
// shore at 49 N) without overlapping anything measurable.
double fatness(double twiceArea, double ax, double ay, double bx, double by, double cx, double cy) {
  const auto squared = [](double dx, double dy) { return dx * dx + dy * dy; };
  const double longest = std::max({squared(bx - ax, by - ay), squared(cx - bx, cy - by), squared(ax - cx, ay - cy)});
  return longest > 0 ? std::fabs(twiceArea) / longest : 0;
}

constexpr double kSliver = 1e-3;

}  // namespace

std::size_t foldedTriangles(const std::vector<TinVertex>& vertices, std::size_t count, const TriangleAt& triangle) {
  // +1 where the grid and the CRS agree on a triangle's turn, -1 where they do not, 0 for none.
  const auto turn = [&](std::size_t i, bool fatOnly) {
    const Triangle& t = triangle(i);
    const TinVertex &a = vertices[t[0]], &b = vertices[t[1]], &c = vertices[t[2]];
    const double grid = cross(gridCol(a), gridRow(a), gridCol(b), gridRow(b), gridCol(c), gridRow(c));
    const double map = cross(a.x, a.y, b.x, b.y, c.x, c.y);
    if (grid == 0 || map == 0) return 0;
    if (fatOnly && (fatness(grid, gridCol(a), gridRow(a), gridCol(b), gridRow(b), gridCol(c), gridRow(c)) < kSliver ||
                    fatness(map, a.x, a.y, b.x, b.y, c.x, c.y) < kSliver))
      return 0;  // a sliver on either side says nothing of a fold
    return (grid > 0) == (map > 0) ? 1 : -1;
  };
  std::int64_t balance = 0;
  for (std::size_t i = 0; i < count; ++i) balance += turn(i, false);
  // A north-up grid's rows run south, so most triangles turn: the fewer are the folded, and
  // only those are weighed for slivers.
  const int folded = balance >= 0 ? -1 : 1;
  std::size_t out = 0;
  for (std::size_t i = 0; i < count; ++i) out += turn(i, true) == folded;
  return out;
}

double heightGap(const Dem& dem, const CrsTransform& toTin, const std::vector<TinVertex>& vertices, std::size_t count,
                 const TriangleAt& triangle) {
  if (toTin.isIdentity()) return 0;
  // A chunk at a time: a fine TIN's centres would take a copy of its size; a chunk PROJ cannot
  // take (its reason is the run's error where it matters) is passed over.
  constexpr std::size_t kChunk = 1 << 16;
  double gap = 0;
  std::vector<std::size_t> over;
  std::vector<double> x, y;
  for (std::size_t start = 0; start < count; start += kChunk) {
    over.clear(), x.clear(), y.clear();
    for (std::size_t i = start; i < std::min(count, start + kChunk); ++i) {
      const Triangle& t = triangle(i);
      double col = 0, row = 0;
      for (VertexId v : t) col += gridCol(vertices[v]) / 3, row += gridRow(vertices[v]) / 3;
      // Only centres over data: across a void no DEM cell tells the two readings apart.
      if (!dem.valid(static_cast<int>(std::floor(row)), static_cast<int>(std::floor(col)))) continue;
      over.push_back(i);
      x.push_back(dem.geotransform[0] + col * dem.geotransform[1]);
      y.push_back(dem.geotransform[3] + row * dem.geotransform[5]);
    }
    try {
      toTin.apply(x, y);
    } catch (const Error&) {
      continue;
    }
    for (std::size_t k = 0; k < over.size(); ++k) {
      const Triangle& t = triangle(over[k]);
      const TinVertex &a = vertices[t[0]], &b = vertices[t[1]], &c = vertices[t[2]];
      const double area = cross(a.x, a.y, b.x, b.y, c.x, c.y);
      if (area == 0) continue;
      // The centre's barycentric weights in the TIN's CRS; on the grid they are a third each.
      const double wa = cross(x[k], y[k], b.x, b.y, c.x, c.y) / area, wb = cross(a.x, a.y, x[k], y[k], c.x, c.y) / area;
      gap = std::max(gap, std::fabs(wa * a.z + wb * b.z + (1 - wa - wb) * c.z - (a.z + b.z + c.z) / 3));
    }
  }
  return gap;
}

void checkGridBend(const Dem& dem, const CrsTransform& toTin, const std::vector<TinVertex>& vertices, std::size_t turnCount,
                   const TriangleAt& turnAt, std::size_t gapCount, const TriangleAt& gapAt, double maxError,
                   const std::string& what, const ProgressRange& progress) {
  if (const std::size_t folded = foldedTriangles(vertices, turnCount, turnAt); folded > 0)
    throw Error("the TIN's CRS, " + toTin.targetName() + ", turns " + std::to_string(folded) +
                " of its triangles over against the DEM's grid, where tinlod measures them (a DEM that wraps the globe, or "
                "reaches a pole): warp the DEM to a projected CRS first (gdalwarp -t_srs), so that its grid is the "
                "TIN's plane, or cut it into regions");
  const double gap = heightGap(dem, toTin, vertices, gapCount, gapAt);
  // A quarter of the largest error: swiss_alps' coarsest level parts by 84 m at one centre, 7 %
  // of its 1255 m, yet its RMSE read in the CRS is within 0.4 % of the grid's.
  if (!(gap > 0.25 * maxError) || !(gap > 0.01)) return;
  progress.warn("read in its CRS (" + toTin.targetName() + "), " + what + "'s triangles part by up to " +
                formatNumber(std::round(gap * 100) / 100) + " m at their centres from their heights on the DEM's grid, "
                "where tinlod measures its errors (at most " + formatNumber(std::round(maxError * 100) / 100) +
                " m): the CRS bends the grid (near a pole, or over a wide DEM); for figures that hold in the CRS, warp "
                "the DEM to it first (gdalwarp -t_srs)");
}

}  // namespace tinlod
