// SPDX-License-Identifier: GPL-3.0-or-later
#include "candidate_scanner.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace tinlod {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

std::int64_t floorDiv(std::int64_t a, std::int64_t b) {
  std::int64_t q = a / b;
  if (a % b != 0 && ((a < 0) != (b < 0))) --q;
  return q;
}
std::int64_t ceilDiv(std::int64_t a, std::int64_t b) { return -floorDiv(-a, b); }


// Twice the signed area of (p, q, r): exact for the whole cell numbers of the cells mode.
double orient(double px, double py, double qx, double qy, double rx, double ry) {
  return (qx - px) * (ry - py) - (qy - py) * (rx - px);
}

}  // namespace

CandidateScanner::CandidateScanner(const InsertGrid& grid) : grid_(grid) {
  const std::size_t cells = std::size_t(grid.cols) * grid.rows;
  for (std::size_t i = 0; i < cells && !holes_; ++i) holes_ = !valid(i);
  if (holes_) {
    edgeOfHole_.assign(cells, 0);
    for (int r = 0; r < grid.rows; ++r)
      for (int c = 0; c < grid.cols; ++c) {
        if (!valid(std::size_t(r) * grid.cols + c)) continue;
        for (int dr = -1; dr <= 1; ++dr)
          for (int dc = -1; dc <= 1; ++dc) {
            const int rr = r + dr, cc = c + dc;
            if (rr >= 0 && cc >= 0 && rr < grid.rows && cc < grid.cols && !valid(std::size_t(rr) * grid.cols + cc))
              edgeOfHole_[std::size_t(r) * grid.cols + c] = 1;
          }
      }
  }
  if (!grid.samples.empty()) {
    sampleOfCell_.assign(cells, -1);
    for (std::size_t i = 0; i < grid.samples.size(); ++i)
      sampleOfCell_[std::size_t(grid.samples[i].cellRow) * grid.cols + grid.samples[i].cellCol] = std::int32_t(i);
  }
}

double CandidateScanner::col(std::uint32_t id) const {
  return grid_.samples.empty() ? double(id % std::uint32_t(grid_.cols)) : grid_.samples[id].col;
}
double CandidateScanner::height(std::uint32_t id) const {
  return grid_.samples.empty() ? grid_.z[id] : grid_.samples[id].z;
}
double CandidateScanner::row(std::uint32_t id) const {
  return grid_.samples.empty() ? double(id / std::uint32_t(grid_.cols)) : grid_.samples[id].row;
}

std::vector<std::uint32_t> CandidateScanner::hullCandidates() const {
  std::vector<std::uint32_t> out;
  if (!grid_.samples.empty()) {
    out.resize(grid_.samples.size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = std::uint32_t(i);
    return out;
  }
  // The first and last valid cell of each row hold every extreme point.
  for (int r = 0; r < grid_.rows; ++r) {
    const std::size_t base = std::size_t(r) * grid_.cols;
    int first = 0, last = grid_.cols - 1;
    while (first < grid_.cols && !valid(base + first)) ++first;
    while (last > first && !valid(base + last)) --last;
    if (first == grid_.cols) continue;
    out.push_back(std::uint32_t(base + first));
    if (last != first) out.push_back(std::uint32_t(base + last));
  }
  return out;
}

ScanResult CandidateScanner::scan(const std::array<std::uint32_t, 3>& corners) const {
  ScanResult result;
  if (!grid_.samples.empty())
    result = scanSamples(corners);
  else
    result = holes_ ? scanCells<true>(corners) : scanCells<false>(corners);
  if (std::isinf(result.error)) result.candidate = splitCandidate(corners);
  return result;
}

// Exact spans: with whole-number corners the edge functions are integers, so a cell on an
// edge is scanned by both triangles and none is missed.
template <bool kHoles>
ScanResult CandidateScanner::scanCells(std::array<std::uint32_t, 3> c) const {
  const std::int64_t cols = grid_.cols;
  std::int64_t x[3], y[3];
  for (int k = 0; k < 3; ++k) x[k] = c[k] % cols, y[k] = c[k] / cols;
  if ((x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]) < 0) {
    std::swap(x[1], x[2]), std::swap(y[1], y[2]), std::swap(c[1], c[2]);
  }
  const float* z = grid_.z;
  const TrianglePlane plane = TrianglePlane::through(x[0], y[0], z[c[0]], x[1], y[1], z[c[1]], x[2], y[2], z[c[2]]);
  const std::int64_t minX = std::min({x[0], x[1], x[2]}), maxX = std::max({x[0], x[1], x[2]});
  const std::int64_t minY = std::min({y[0], y[1], y[2]}), maxY = std::max({y[0], y[1], y[2]});
  double best = 0;
  std::int64_t bestCell = c[0];
  std::size_t validCells = 0;
  bool missing = false;
  for (std::int64_t yy = minY; yy <= maxY; ++yy) {
    std::int64_t xl = minX, xr = maxX;
    for (int k = 0; k < 3; ++k) {
      const int n = (k + 1) % 3;
      // Inside edge k when K - D x >= 0.
      const std::int64_t D = y[n] - y[k], K = (x[n] - x[k]) * (yy - y[k]) + D * x[k];
      if (D > 0) xr = std::min(xr, floorDiv(K, D));
      else if (D < 0) xl = std::max(xl, ceilDiv(K, D));
      else if (K < 0) xr = xl - 1;
    }
    if (xl > xr) continue;
    const float* h = z + yy * cols;
    const double base = plane.height(double(xl), double(yy));
    double rowBest = 0;
    std::int64_t rowArg = -1;
    for (std::int64_t xx = xl; xx <= xr; ++xx) {
      const double e = std::fabs(base + plane.dzdx * double(xx - xl) - h[xx]);
      if constexpr (kHoles) {
        if (e != e) {
          missing = true;
          continue;
        }
        ++validCells;
      }
      // Without a branch: which cell is worst is data, and mispredicted jumps cost more
      // than the two selects (the first of equal errors still wins).
      const bool worse = e > rowBest;
      rowBest = worse ? e : rowBest;
      rowArg = worse ? xx : rowArg;
    }
    if (rowBest > best) best = rowBest, bestCell = yy * cols + rowArg;
  }
  ScanResult result;
  result.overHole = missing;
  if (missing && validCells > 3) {
    result.error = kInfinity;
    return result;
  }
  // The worst point a corner: every other is within rounding of the plane.
  if (bestCell == std::int64_t(c[0]) || bestCell == std::int64_t(c[1]) || bestCell == std::int64_t(c[2])) best = 0;
  result.error = missing ? 0 : best;
  result.candidate = std::uint32_t(bestCell);
  return result;
}

TrianglePlane CandidateScanner::planeOf(const std::array<std::uint32_t, 3>& c) const {
  double x[3], y[3], z[3];
  for (int k = 0; k < 3; ++k) x[k] = col(c[k]), y[k] = row(c[k]), z[k] = height(c[k]);
  return TrianglePlane::through(x[0], y[0], z[0], x[1], y[1], z[1], x[2], y[2], z[2]);
}

// The cells around the triangle, one more on each side: a sampled point lies within a
// cell of its cell's centre.
CandidateScanner::CellBlock CandidateScanner::blockAround(const std::array<std::uint32_t, 3>& c) const {
  double x[3], y[3];
  for (int k = 0; k < 3; ++k) x[k] = col(c[k]), y[k] = row(c[k]);
  return {std::max(0, int(std::floor(std::min({y[0], y[1], y[2]}))) - 1),
          std::min(grid_.rows - 1, int(std::ceil(std::max({y[0], y[1], y[2]}))) + 1),
          std::max(0, int(std::floor(std::min({x[0], x[1], x[2]}))) - 1),
          std::min(grid_.cols - 1, int(std::ceil(std::max({x[0], x[1], x[2]}))) + 1)};
}

bool CandidateScanner::inside(const std::array<std::uint32_t, 3>& c, double px, double py) const {
  double x[3], y[3];
  for (int k = 0; k < 3; ++k) x[k] = col(c[k]), y[k] = row(c[k]);
  const double area = orient(x[0], y[0], x[1], y[1], x[2], y[2]);
  // A hair of tolerance for sampled points: one on an edge counts for both triangles.
  const double tol = grid_.samples.empty() ? 0 : 1e-12 * std::fabs(area);
  const double s = area > 0 ? 1 : -1;
  for (int k = 0; k < 3; ++k) {
    const int n = (k + 1) % 3;
    if (s * orient(x[k], y[k], x[n], y[n], px, py) < -tol) return false;
  }
  return true;
}

// As `tinlod sample` decides: a triangle spans a hole when the closed triangle of its
// corners' cell centres holds a missing cell's centre. Exact in whole numbers.
bool CandidateScanner::footprintHolds(const std::array<std::uint32_t, 3>& c, int col, int row) const {
  double x[3], y[3];
  for (int k = 0; k < 3; ++k) x[k] = grid_.samples[c[k]].cellCol, y[k] = grid_.samples[c[k]].cellRow;
  const double area = orient(x[0], y[0], x[1], y[1], x[2], y[2]);
  bool allNonNegative = true, allNonPositive = true;
  for (int k = 0; k < 3; ++k) {
    const int n = (k + 1) % 3;
    const double o = orient(x[k], y[k], x[n], y[n], col, row);
    allNonNegative &= o >= 0, allNonPositive &= o <= 0;
  }
  if (area != 0) return area > 0 ? allNonNegative : allNonPositive;
  // Collinear centres: the footprint is a segment (allNonNegative and allNonPositive: on its line).
  return allNonNegative && allNonPositive && col >= std::min({x[0], x[1], x[2]}) && col <= std::max({x[0], x[1], x[2]}) &&
         row >= std::min({y[0], y[1], y[2]}) && row <= std::max({y[0], y[1], y[2]});
}

// Sampled candidates lie within a cell of their cell's centre: the block of cells around
// the triangle holds them all, and its missing cells are tested at their centres.
ScanResult CandidateScanner::scanSamples(const std::array<std::uint32_t, 3>& c) const {
  const TrianglePlane plane = planeOf(c);
  const CellBlock b = blockAround(c);
  ScanResult result;
  std::size_t others = 0;
  for (int r = b.r0; r <= b.r1; ++r)
    for (int cc = b.c0; cc <= b.c1; ++cc) {
      const std::size_t cell = std::size_t(r) * grid_.cols + cc;
      const std::int32_t s = sampleOfCell_[cell];
      if (s < 0) {
        if (holes_ && !valid(cell) && footprintHolds(c, cc, r)) result.overHole = true;
        continue;
      }
      const std::uint32_t id = std::uint32_t(s);
      if (id == c[0] || id == c[1] || id == c[2]) continue;
      const CandidatePoint& p = grid_.samples[id];
      if (!inside(c, p.col, p.row)) continue;
      ++others;
      const double e = std::fabs(plane.height(p.col, p.row) - p.z);
      if (e > result.error) result.error = e, result.candidate = id;
    }
  if (result.overHole) result.error = others > 0 ? kInfinity : 0;
  return result;
}

// A triangle over a hole and over data: split it at a candidate on the hole's edge if it
// has one (the outline the TIN must follow), else at any; the worst first.
std::uint32_t CandidateScanner::splitCandidate(const std::array<std::uint32_t, 3>& c) const {
  const TrianglePlane plane = planeOf(c);
  const CellBlock b = blockAround(c);
  std::uint32_t best = c[0];
  std::pair<bool, double> bestKey{false, -1};
  for (int r = b.r0; r <= b.r1; ++r)
    for (int cc = b.c0; cc <= b.c1; ++cc) {
      const std::size_t cell = std::size_t(r) * grid_.cols + cc;
      std::uint32_t id;
      double px, py, pz;
      if (grid_.samples.empty()) {
        if (!valid(cell)) continue;
        id = std::uint32_t(cell), px = cc, py = r, pz = grid_.z[cell];
      } else {
        if (sampleOfCell_[cell] < 0) continue;
        id = std::uint32_t(sampleOfCell_[cell]);
        const CandidatePoint& p = grid_.samples[id];
        px = p.col, py = p.row, pz = p.z;
      }
      if (id == c[0] || id == c[1] || id == c[2] || !inside(c, px, py)) continue;
      // Cells on a hole's edge rank above all others; among each kind, the worst first.
      const std::pair<bool, double> key{edgeOfHole_[cell] != 0, std::fabs(plane.height(px, py) - pz)};
      if (key > bestKey) bestKey = key, best = id;
    }
  return best;
}

template ScanResult CandidateScanner::scanCells<true>(std::array<std::uint32_t, 3>) const;
template ScanResult CandidateScanner::scanCells<false>(std::array<std::uint32_t, 3>) const;

}  // namespace tinlod
