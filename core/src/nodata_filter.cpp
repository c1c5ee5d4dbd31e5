// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/nodata_filter.h"

#include <algorithm>
#include <cstdint>

namespace tinlod {
namespace {

// Missing cells counted per row prefix, so that a row segment is counted in O(1) and a
// triangle in O(rows it spans), however large the hole under it.
class MissingCounts {
 public:
  // Nothing is counted on a DEM without holes (the common case: 4 bytes a cell saved).
  explicit MissingCounts(const Dem& dem) : width_(dem.width) {
    any_ = std::any_of(dem.z.begin(), dem.z.end(), [](float v) { return v != v; });
    if (!any_) return;
    counts_.resize((dem.width + 1) * std::size_t(dem.height));
    for (int row = 0; row < dem.height; ++row) {
      std::uint32_t* c = &counts_[row * std::size_t(width_ + 1)];
      c[0] = 0;
      for (int col = 0; col < width_; ++col) c[col + 1] = c[col] + !dem.valid(row, col);
    }
  }
  bool any() const { return any_; }
  // Missing cells in columns [c0, c1] of a row; off-raster columns count as missing.
  std::int64_t inRow(int row, std::int64_t c0, std::int64_t c1) const {
    if (c0 > c1) return 0;
    std::int64_t outside = std::max<std::int64_t>(0, -c0) + std::max<std::int64_t>(0, c1 - (width_ - 1));
    c0 = std::max<std::int64_t>(c0, 0);
    c1 = std::min<std::int64_t>(c1, width_ - 1);
    const std::uint32_t* c = &counts_[row * std::size_t(width_ + 1)];
    return outside + (c0 <= c1 ? c[c1 + 1] - c[c0] : 0);
  }

 private:
  int width_;
  std::vector<std::uint32_t> counts_;
  bool any_ = false;
};

std::int64_t floorDiv(std::int64_t n, std::int64_t d) { return n >= 0 ? n / d : -((-n + d - 1) / d); }
std::int64_t ceilDiv(std::int64_t n, std::int64_t d) { return -floorDiv(-n, d); }

struct GridPoint {
  std::int64_t col, row;
};

// The columns where a closed triangle with lattice-point corners meets an integer row,
// exactly: integer arithmetic on cell indices, no rounding anywhere. ceil and floor
// are monotone, so the extreme lattice columns are the extremes over the edges.
bool rowSpan(const GridPoint (&p)[3], std::int64_t row, std::int64_t& lo, std::int64_t& hi) {
  lo = INT64_MAX;
  hi = INT64_MIN;
  for (int i = 0; i < 3; ++i) {
    GridPoint a = p[i], b = p[(i + 1) % 3];
    if (row < std::min(a.row, b.row) || row > std::max(a.row, b.row)) continue;
    if (a.row == b.row) {
      lo = std::min({lo, a.col, b.col});
      hi = std::max({hi, a.col, b.col});
      continue;
    }
    if (a.row > b.row) std::swap(a, b);
    const std::int64_t num = a.col * (b.row - a.row) + (row - a.row) * (b.col - a.col);
    const std::int64_t den = b.row - a.row;
    lo = std::min(lo, ceilDiv(num, den));
    hi = std::max(hi, floorDiv(num, den));
  }
  return lo <= hi;
}

bool coversMissing(const MissingCounts& missing, const GridPoint (&p)[3]) {
  const std::int64_t r0 = std::min({p[0].row, p[1].row, p[2].row});
  const std::int64_t r1 = std::max({p[0].row, p[1].row, p[2].row});
  for (std::int64_t row = r0; row <= r1; ++row) {
    std::int64_t lo, hi;
    if (rowSpan(p, row, lo, hi) && missing.inRow(static_cast<int>(row), lo, hi) > 0) return true;
  }
  return false;
}

GridPoint gridPoint(const TinVertex& v) { return {v.col, v.row}; }

bool collinearInGrid(const GridPoint (&p)[3]) {
  return (p[1].col - p[0].col) * (p[2].row - p[0].row) == (p[2].col - p[0].col) * (p[1].row - p[0].row);
}

class TriangleFilter {
 public:
  TriangleFilter(const Dem& dem, const Triangulation& triangulation, const Tin& tin)
      : missing_(dem), triangulation_(triangulation), tin_(tin), keep_(triangulation.triangles.size(), true) {}

  // Corners are cells of the raster, so without a missing cell no triangle can cover one:
  // on a DEM without holes this pass over every triangle would find nothing.
  void dropOverNodata(const ProgressRange& progress) {
    if (!missing_.any()) return;
    for (std::size_t t = 0; t < keep_.size(); ++t) {
      if ((t & 0xFFFF) == 0) progress.report(0.5 * t / keep_.size(), "Cutting out nodata");
      keep_[t] = !coversMissing(missing_, corners(t));
    }
  }

  void peelBoundarySlivers(const ProgressRange& progress) {
    std::vector<std::int32_t> queue;
    for (std::size_t t = 0; t < keep_.size(); ++t) {
      if ((t & 0xFFFF) == 0) progress.report(0.5 + 0.5 * t / keep_.size(), "Cutting out nodata");
      if (isBoundarySliver(t)) queue.push_back(static_cast<std::int32_t>(t));
    }
    while (!queue.empty()) {
      const std::int32_t t = queue.back();
      queue.pop_back();
      if (!isBoundarySliver(t)) continue;
      keep_[t] = false;
      for (std::int32_t n : triangulation_.neighbours[t])
        if (n != kNoNeighbour && isBoundarySliver(n)) queue.push_back(n);
    }
  }

  std::vector<Triangle> kept() const {
    std::vector<Triangle> out;
    for (std::size_t t = 0; t < keep_.size(); ++t)
      if (keep_[t]) out.push_back(triangulation_.triangles[t]);
    return out;
  }

  // The kept triangles' neighbours, renumbered as kept() numbers them; a dropped
  // neighbour leaves an outline edge.
  std::vector<std::array<std::int32_t, 3>> keptNeighbours() const {
    std::vector<std::int32_t> newIndex(keep_.size(), kNoNeighbour);
    std::int32_t next = 0;
    for (std::size_t t = 0; t < keep_.size(); ++t)
      if (keep_[t]) newIndex[t] = next++;
    std::vector<std::array<std::int32_t, 3>> out;
    out.reserve(static_cast<std::size_t>(next));
    for (std::size_t t = 0; t < keep_.size(); ++t) {
      if (!keep_[t]) continue;
      std::array<std::int32_t, 3> n = triangulation_.neighbours[t];
      for (std::int32_t& u : n) u = u == kNoNeighbour ? kNoNeighbour : newIndex[u];
      out.push_back(n);
    }
    return out;
  }

 private:
  using Corners = GridPoint[3];
  const Corners& corners(std::size_t t) {
    for (int k = 0; k < 3; ++k) scratch_[k] = gridPoint(tin_.vertices[triangulation_.triangles[t][k]]);
    return scratch_;
  }
  bool isBoundarySliver(std::size_t t) {
    if (!keep_[t] || !collinearInGrid(corners(t))) return false;
    for (std::int32_t n : triangulation_.neighbours[t])
      if (n == kNoNeighbour || !keep_[n]) return true;
    return false;
  }

  MissingCounts missing_;
  const Triangulation& triangulation_;
  const Tin& tin_;
  std::vector<bool> keep_;
  Corners scratch_;
};

}  // namespace

namespace {

TriangleFilter filterOnValidData(const Dem& dem, const Triangulation& triangulation, const Tin& tin,
                                 const ProgressRange& progress) {
  TriangleFilter filter(dem, triangulation, tin);
  filter.dropOverNodata(progress);
  filter.peelBoundarySlivers(progress);
  return filter;
}

}  // namespace

std::vector<Triangle> trianglesOnValidData(const Dem& dem, const Triangulation& triangulation, const Tin& tin,
                                           std::vector<std::array<std::int32_t, 3>>* neighbours,
                                           const ProgressRange& progress) {
  const TriangleFilter filter = filterOnValidData(dem, triangulation, tin, progress);
  if (neighbours) *neighbours = filter.keptNeighbours();
  return filter.kept();
}

std::size_t keepTrianglesOnValidData(const Dem& dem, const Triangulation& triangulation, Tin& tin,
                                     const ProgressRange& progress) {
  const TriangleFilter filter = filterOnValidData(dem, triangulation, tin, progress.sub(0, 0.9));
  tin.triangles = filter.kept();
  tin.neighbours = filter.keptNeighbours();
  progress.report(0.9, "Cutting out nodata");
  const std::size_t before = tin.vertices.size();
  return before - dropUnusedVertices(tin).size();
}

}  // namespace tinlod
