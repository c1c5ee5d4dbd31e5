// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the DEM cells under a triangle, for measuring a TIN against its DEM at every
// valid cell centre. A triangle is taken in the DEM's grid, where its corners lie at
// their cells plus the jitter (TinVertex::dcol, drow), and its height there is the linear
// interpolation of its corners'; for a projected DEM that is exactly the TIN's plane, and
// for one in degrees the grid bends against the TIN's metric CRS by millimetres across a
// kilometre-sized triangle. It is the same reading of a TIN as the accuracy evaluation's.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "tinlod/dem.h"
#include "tinlod/tin.h"
#include "tinlod/triangle_plane.h"

namespace tinlod {

// A triangle corner in the grid: column, row, height and TIN id (which orders each edge
// the same way for both triangles on it).
struct CellCorner {
  double c, r, z;
  VertexId id;
};

inline CellCorner cellCorner(const TinVertex& v, VertexId id) {
  return {v.col + double(v.dcol), v.row + double(v.drow), v.z, id};
}

// Calls visit(row, col, height) for each cell centre of the raster `width` x `height` in
// the triangle. Across a shared edge the two triangles take each centre exactly once (but
// a centre that is exactly a vertex where two outline edges meet, such as a raster corner,
// which both triangles of those edges may take; its distance is 0 there):
// every edge is evaluated from its smaller id, in the same floating-point operations for
// both, and a centre exactly on it goes to the side a tiny step (+e, +e^2) would reach
// (symbolic perturbation). `outline[k]` marks the edge opposite corner k as an outline
// edge, which has no triangle beyond and keeps the centres on it. Degenerate triangles
// take none.
template <class Visit>
void scanCells(int width, int height, const CellCorner (&p)[3], const bool (&outline)[3], Visit visit) {
  const double area2 = (p[1].c - p[0].c) * (p[2].r - p[0].r) - (p[2].c - p[0].c) * (p[1].r - p[0].r);
  if (!(area2 != 0) || !std::isfinite(area2)) return;
  const double s = area2 > 0 ? 1 : -1;
  struct Edge {
    const CellCorner* lo;  // the smaller id
    double dc, dr;         // hi - lo
    double sign;           // +1 or -1: the edge function's sign inside the triangle
    bool tieInside;        // a centre on the edge belongs to this triangle
  };
  Edge e[3];
  for (int k = 0; k < 3; ++k) {
    const CellCorner &a = p[(k + 1) % 3], &b = p[(k + 2) % 3];
    const bool forward = a.id < b.id;
    const CellCorner &lo = forward ? a : b, &hi = forward ? b : a;
    const double dc = hi.c - lo.c, dr = hi.r - lo.r;
    const double sign = s * (forward ? 1 : -1);
    // d/dc of the edge function is -dr, d/dr is dc: the sign a step (+e, +e^2) takes.
    const double step = dr != 0 ? -dr : dc;
    e[k] = {&lo, dc, dr, sign, outline[k] || sign * step > 0};
  }
  const double rowMin = std::min({p[0].r, p[1].r, p[2].r}), rowMax = std::max({p[0].r, p[1].r, p[2].r});
  const double colMin = std::min({p[0].c, p[1].c, p[2].c}), colMax = std::max({p[0].c, p[1].c, p[2].c});
  const int r0 = std::max(0, static_cast<int>(std::ceil(rowMin))), r1 = std::min(height - 1, static_cast<int>(std::floor(rowMax)));
  const int c0 = std::max(0, static_cast<int>(std::ceil(colMin))), c1 = std::min(width - 1, static_cast<int>(std::floor(colMax)));
  // The plane, for heights only: which cells are inside is decided by the edge functions.
  const TrianglePlane plane = TrianglePlane::through(p[0].c, p[0].r, p[0].z, p[1].c, p[1].r, p[1].z, p[2].c, p[2].r, p[2].z);
  for (int row = r0; row <= r1; ++row) {
    // Each edge's function along the row is rowTerm - dr (col - lo.c), the same operations
    // in both triangles of the edge, and monotone in col even rounded: the cells inside
    // make one run. Its ends are found in floating point with a cell to spare, then tested
    // exactly from each end.
    double rowTerm[3], left = c0, right = c1;
    for (int k = 0; k < 3; ++k) {
      rowTerm[k] = e[k].dc * (row - e[k].lo->r);
      const double slope = -e[k].dr * e[k].sign;  // of sign * edge function, per column
      if (slope == 0) continue;
      const double at = e[k].lo->c + rowTerm[k] / e[k].dr;  // where it crosses zero
      if (slope > 0) left = std::max(left, std::floor(at) - 1);
      else right = std::min(right, std::ceil(at) + 1);
    }
    auto inside = [&](int col) {
      for (int k = 0; k < 3; ++k) {
        const double w = e[k].sign * (rowTerm[k] - e[k].dr * (col - e[k].lo->c));
        if (!(w > 0 || (w == 0 && e[k].tieInside))) return false;
      }
      return true;
    };
    int first = static_cast<int>(left), last = static_cast<int>(right);
    while (first <= last && !inside(first)) ++first;
    while (last >= first && !inside(last)) --last;
    // From corner 0, so that a flat triangle gives its height exactly.
    for (int col = first; col <= last; ++col) visit(row, col, plane.height(col, row));
  }
}

}  // namespace tinlod
