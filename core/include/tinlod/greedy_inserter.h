// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include "tinlod/feedback.h"
#include "tinlod/tin.h"
#include "tinlod/triangulation.h"

namespace tinlod {

// A candidate point that is not a cell centre: a vertex of a sampled TIN.
struct CandidatePoint {
  double col = 0, row = 0;  // position in DEM cell units (cell centres at whole numbers)
  float z = 0;
  std::int32_t cellRow = 0, cellCol = 0;  // the DEM cell it was sampled from
};

// What greedy insertion works on: the DEM's heights and its candidates.
struct InsertGrid {
  int cols = 0, rows = 0;
  const float* z = nullptr;      // cols x rows heights, row-major, NaN where missing
  // Metres between cell centres along a row and along a column at the DEM's centre. The
  // triangulation is Delaunay for (col * p, row * q), p / q the ratio of the two as whole
  // numbers (q <= 4096): the shape of the cells on the ground, kept exact. That is the
  // TIN's CRS up to scale for a projected DEM, and for a geographic one its grid at the
  // ground scale of its centre (a UTM zone bends the grid slightly, which only breaks the
  // grid's ties between cocircular cells differently). Triangles are straight in the grid,
  // where the candidates are scanned and where `tinlod accuracy` measures.
  double cellWidth = 1;
  double cellHeight = 1;
  // Empty: every valid cell is a candidate (id = row * cols + col). Otherwise these
  // points are the candidates (id = index) and the cells only mark the holes.
  std::vector<CandidatePoint> samples;
};

struct InsertStop {
  double maxError = 0;           // stop when every candidate is within this (metres)
  std::size_t maxVertices = 0;   // 0: no limit
  std::size_t maxTriangles = 0;  // 0: no limit
};

// The cells' shape on the ground as a ratio of small whole numbers {p, q} (q <= 4096,
// within 1e-7 or as close as that allows): the triangulation is Delaunay for
// (col * p, row * q). Coordinates stay exact, so cells cocircular on the ground stay
// exactly cocircular and ties are broken by the data, not by the rounding of metres
// (which cost 3 % more vertices on 88.814 m cells).
std::array<double, 2> delaunayScales(double cellWidth, double cellHeight);

struct InsertedVertex {
  std::uint32_t candidate = 0;
  // The largest vertical error of the TIN of the vertices inserted before this one (this
  // vertex was its worst point): any prefix of the insertion order is a coarser TIN whose
  // maximum error is the next vertex's errorBefore. NaN for the starting hull;
  // infinity for a vertex inserted to keep triangles off a nodata hole.
  double errorBefore = std::numeric_limits<double>::quiet_NaN();
};

// Garland and Heckbert's greedy insertion: starting from the convex hull of the
// candidates, repeatedly inserts the candidate of largest vertical error into a
// Delaunay triangulation (CGAL, exact predicates). Each triangle keeps its worst
// candidate; a priority queue gives the next; after an insertion only the triangles
// around the new vertex are rescanned. A triangle over missing cells is split first
// (at its candidate on the hole's edge of largest error, if it has one) until no triangle mixes
// data and holes.
class GreedyInserter {
 public:
  GreedyInserter(InsertGrid grid, const ProgressRange& progress);
  ~GreedyInserter();
  GreedyInserter(const GreedyInserter&) = delete;
  GreedyInserter& operator=(const GreedyInserter&) = delete;

  // Inserts until every candidate is within stop.maxError or a count limit is reached.
  // Now and then (every thousand or so insertions, and at the end) `every` is called,
  // on this thread: for whoever takes the vertices as they come.
  void run(const InsertStop& stop, const ProgressRange& progress, const std::function<void()>& every = {});

  std::size_t vertexCount() const;
  std::size_t triangleCount() const;  // of the whole triangulation, holes included
  // The largest error of any candidate now: 0 when exact, infinity while a triangle
  // still spans a hole.
  double maxError() const;
  const std::vector<InsertedVertex>& inserted() const;
  // Every triangle with its neighbours, indexing inserted(); counter-clockwise in cell
  // units (col, row), which is clockwise on a north-up map. Those over holes are included:
  // trianglesOnValidData (nodata_filter.h) keeps the others, as `tinlod sample` does.
  // Reports over `progress` (a second for a few million triangles: a stop is heard).
  Triangulation triangulation(const ProgressRange& progress = ProgressRange(Feedback{}, 0, 1)) const;
  // Where a candidate is, in cell units.
  double candidateCol(std::uint32_t candidate) const;
  double candidateRow(std::uint32_t candidate) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tinlod
