// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/tin_rasterizer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "parallel_blocks.h"

namespace tinlod {
namespace {

using Pos = std::array<double, 2>;

// A hair of tolerance so that points on an edge are never missed by both of its
// triangles through rounding; both then write the same height.
constexpr double kEdgeTolerance = 1e-9;

struct Plane {
  Pos a, b, c;
  double za, zb, zc, area;
  double top, bottom;  // smallest and largest row coordinate
};

double edge(const Pos& p, const Pos& q, double x, double y) { return (q[0] - p[0]) * (y - p[1]) - (q[1] - p[1]) * (x - p[0]); }

// A row or column of a position that may lie far off the grid (a vertex of a damaged
// file, or one a CRS could not transform): clamped before the conversion, which is
// undefined beyond the range of int.
int clampedIndex(double v, int lo, int hi) { return static_cast<int>(std::clamp(v, double(lo), double(hi))); }

// The columns of row r that fillTriangle's test can accept, a column wider each way for
// rounding, within [c0, c1]: along a row each edge's test is linear, so each edge bounds
// the row on one side, tolerance included. The test still decides; a thin triangle just
// no longer costs its whole bounding box. An edge within a thousandth of a row of
// horizontal is left out: its bound would be swamped by rounding.
void rowSpan(const Plane& t, double tol, int r, int& c0, int& c1) {
  double lo = c0, hi = c1;
  const std::array<const Pos*, 2> edges[3] = {{&t.b, &t.c}, {&t.c, &t.a}, {&t.a, &t.b}};
  for (const auto& [p, q] : edges) {
    const double dy = (*q)[1] - (*p)[1];
    if (std::fabs(dy) < 1e-3) continue;
    // Where edge(p, q, x, r) reaches -tol (a counter-clockwise triangle) or tol (clockwise).
    const double x = (*p)[0] + (((*q)[0] - (*p)[0]) * (r - (*p)[1]) + (t.area > 0 ? tol : -tol)) / dy;
    if ((t.area > 0) == (dy > 0)) hi = std::min(hi, x);
    else lo = std::max(lo, x);
  }
  c0 = clampedIndex(std::floor(lo) - 1, c0, c1 + 1);
  c1 = clampedIndex(std::ceil(hi) + 1, c0 - 1, c1);
}

// The grid filled: `cols` x `rows` points from point (col0, row0) of the positions' grid.
struct Frame {
  int col0 = 0, row0 = 0, cols = 0, rows = 0;
};

// Fills the points of rows [rowBegin, rowEnd) inside one triangle; rows and columns are the
// positions' own, so a window of a grid computes every value as the whole grid does.
void fillTriangle(const Plane& t, int rowBegin, int rowEnd, const Frame& frame, Grid& out) {
  const double tol = kEdgeTolerance * std::fabs(t.area);
  const int r0 = clampedIndex(std::ceil(t.top), rowBegin, rowEnd);
  const int r1 = clampedIndex(std::floor(t.bottom), rowBegin - 1, rowEnd - 1);
  const int lastCol = frame.col0 + frame.cols - 1;
  const int boxC0 = clampedIndex(std::ceil(std::min({t.a[0], t.b[0], t.c[0]})), frame.col0, lastCol + 1);
  const int boxC1 = clampedIndex(std::floor(std::max({t.a[0], t.b[0], t.c[0]})), frame.col0 - 1, lastCol);
  for (int r = r0; r <= r1; ++r) {
    int c0 = boxC0, c1 = boxC1;
    rowSpan(t, tol, r, c0, c1);
    for (int c = c0; c <= c1; ++c) {
      const double wa = edge(t.b, t.c, c, r), wb = edge(t.c, t.a, c, r), wc = edge(t.a, t.b, c, r);
      const bool inside = t.area > 0 ? (wa >= -tol && wb >= -tol && wc >= -tol) : (wa <= tol && wb <= tol && wc <= tol);
      if (inside) out.at(c - frame.col0, r - frame.row0) = (wa * t.za + wb * t.zb + wc * t.zc) / t.area;
    }
  }
}

// The rows planes are ordered by: their top rows, those above the frame included, so that
// the planes of one row keep one order whatever frame they are rasterized in; where they
// overlap (a point on a shared edge, which may round differently from each side) the later
// plane's value stays. Rows far above are bounded: only a damaged file's triangle reaches
// there.
struct RowOrder {
  int lowest = 0, end = 0;
  int of(const Plane& p) const { return clampedIndex(std::floor(p.top), lowest, end); }
  std::size_t slot(const Plane& p) const { return static_cast<std::size_t>(of(p) - lowest); }
};

RowOrder rowOrder(const std::vector<Pos>& positions, const Frame& frame) {
  double top = frame.row0;
  for (const Pos& p : positions)
    if (std::isfinite(p[1])) top = std::min(top, p[1]);
  const int farthest = frame.row0 - 8 * (frame.rows + 1) - 65536;
  return RowOrder{clampedIndex(std::floor(top), farthest, frame.row0), frame.row0 + frame.rows};
}

// False for a triangle without area or with a corner off any grid (not finite).
bool planeOf(const std::vector<Pos>& positions, const std::vector<double>& z, const Triangle& t, Plane& out) {
  const Pos &a = positions[t[0]], &b = positions[t[1]], &c = positions[t[2]];
  const double area = edge(a, b, c[0], c[1]);
  if (area == 0 || !std::isfinite(area)) return false;
  out = {a, b, c, z[t[0]], z[t[1]], z[t[2]], area, std::min({a[1], b[1], c[1]}), std::max({a[1], b[1], c[1]})};
  return true;
}

// A triangle in the rasterizer's order: its top row (RowOrder::of) and its corners. The
// plane itself is computed again where the triangle is filled: 16 bytes a triangle where
// the plane takes 96, which set the peak of measuring a large window, for a few loads and
// products per triangle.
struct Placed {
  Triangle corners;
  std::int32_t topRow;
};

// The triangles in order of their top row, each row's in the triangles' order, which lets
// each band of rows skip to its own. A counting sort that writes each triangle once, in its
// place. `tallest`: the most rows any plane spans.
std::vector<Placed> trianglesByTopRow(const std::vector<Pos>& positions, const std::vector<double>& z,
                                      const std::vector<Triangle>& triangles, const RowOrder& order, double& tallest) {
  std::vector<std::size_t> start(static_cast<std::size_t>(order.end - order.lowest) + 2, 0);
  Plane p;
  tallest = 0;
  for (const Triangle& t : triangles)
    if (planeOf(positions, z, t, p)) {
      ++start[order.slot(p) + 1];
      tallest = std::max(tallest, p.bottom - p.top);
    }
  for (std::size_t r = 1; r < start.size(); ++r) start[r] += start[r - 1];
  std::vector<Placed> sorted(start.back());
  for (const Triangle& t : triangles)
    if (planeOf(positions, z, t, p)) sorted[start[order.slot(p)]++] = Placed{t, order.of(p)};
  return sorted;
}

}  // namespace

Grid rasterizeTin(const std::vector<Pos>& positions, const std::vector<double>& z, const std::vector<Triangle>& triangles,
                  int cols, int rows, const ProgressRange& progress, int col0, int row0) {
  Grid out(cols, rows);
  const Frame frame{col0, row0, cols, rows};
  const RowOrder order = rowOrder(positions, frame);
  double tallest = 0;
  const std::vector<Placed> placed = trianglesByTopRow(positions, z, triangles, order, tallest);
  auto work = [&](int blockBegin, int blockEnd) {
    const int rowBegin = row0 + blockBegin, rowEnd = row0 + blockEnd;
    const int firstRow = clampedIndex(std::floor(rowBegin - tallest) - 1, order.lowest, order.end);
    auto first = std::lower_bound(placed.begin(), placed.end(), firstRow,
                                  [](const Placed& p, int row) { return p.topRow < row; });
    Plane plane;
    // topRow < rowEnd is top < rowEnd: rowEnd is a whole row.
    for (auto it = first; it != placed.end() && it->topRow < rowEnd; ++it) {
      planeOf(positions, z, it->corners, plane);  // true: only planes with area were placed
      if (plane.bottom >= rowBegin) fillTriangle(plane, rowBegin, rowEnd, frame, out);
    }
  };
  forEachBlock(rows, work, [&](double f) { progress.report(f, "Interpolating the TIN"); });
  return out;
}

}  // namespace tinlod
