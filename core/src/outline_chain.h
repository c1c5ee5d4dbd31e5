// SPDX-License-Identifier: GPL-3.0-or-later
// Private: when an outline vertex may go. Deleting it joins its two outline neighbours
// by a straight edge; the outline vertices of level 0 that edge replaces (the vertex and
// those deleted between the neighbours before it) must all lie within the tolerance of it,
// so the outline never moves further than that from the data's own. Where the new edge
// cuts into the data, the cells it gives up are counted. Where it runs outside the TIN
// (the vertex bends the outline inwards), the ground it adds must hold no nodata cell
// centre and no centre off the raster (in the grid, with the vertices where the jitter put
// them and at their cells' centres alike), no other vertex of the TIN, and the two
// neighbours must not be joined already (nor be where two parts of the TIN touch); along a
// raster edge (which a DEM in degrees bends by millimetres in the TIN's metric CRS) it may
// reach at most half a cell past the edge's line of centres, and cut inside it by at most
// 5 % of a cell.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "simplification_mesh.h"
#include "tinlod/hierarchy_locator.h"
#include "tinlod/dem.h"
#include "tinlod/tin.h"

namespace tinlod {

class OutlineChain {
 public:
  OutlineChain() = default;
  // Level 0's outline order, for the open vertices of one fan; where each vertex lies in
  // the DEM's grid, whose cells say where nodata is.
  OutlineChain(const SimplificationMesh& mesh, const Tin& tin, const Dem& dem);

  // A corner of the raster: it stays, so a rectangular DEM keeps its rectangle.
  bool rasterCorner(VertexId v) const;
  // Whether open vertex v, whose open star's ring is `star` (its first ring vertex the
  // outline neighbour after it, its last the one before), may go with the outline moved
  // by at most `tolerance` metres from level 0's (`halfCell` metres past a raster edge).
  // `gone(u)` says whether vertex u was deleted.
  template <class Gone>
  bool allows(const SimplificationMesh& mesh, VertexId v, const Star& star, VertexId after, VertexId before,
              double tolerance, double halfCell, Gone gone) const {
    if (sideOfNewEdge(star) > 0) {
      if (!addsOnlyData(mesh, v, after, before, gone)) return false;
      if (onOneRasterEdge(v, after, before)) tolerance = std::min(tolerance, halfCell);
    } else if (alongOneRasterEdge(v, after, before)) {
      // The edge of a DEM in degrees is a curve in the TIN's CRS: a long straight edge would
      // cut its cells' centres off by metres (6 m on swiss_alps' coarsest level). Within
      // the locator's reach, tinlod locate still finds them.
      tolerance = std::min(tolerance, kRasterEdgeReach * 2 * halfCell);
    }
    bool within = distance(v, after, before) <= tolerance;
    for (VertexId u = before_[v]; within && u != before; u = before_[u]) within = distance(u, after, before) <= tolerance;
    for (VertexId u = after_[v]; within && u != after; u = after_[u]) within = distance(u, after, before) <= tolerance;
    return within;
  }

 private:
  bool onOneRasterEdge(VertexId v, VertexId after, VertexId before) const;
  // Whether the vertex and its two outline neighbours lie on one raster edge's line, a
  // corner of it included (the last stretch of an edge ends at its corner).
  bool alongOneRasterEdge(VertexId v, VertexId after, VertexId before) const;
  // The ground between the vertex and the new edge: no nodata or off-raster centre, no
  // other vertex still there, and the neighbours not joined already.
  template <class Gone>
  bool addsOnlyData(const SimplificationMesh& mesh, VertexId v, VertexId after, VertexId before, Gone gone) const {
    if (coversMissingCell(v, after, before)) return false;
    // Where two parts of the TIN touch, a walk sees one fan: such a neighbour is not joined.
    if (!mesh.deletableOpen(after) || !mesh.deletableOpen(before)) return false;
    bool joined = false;
    mesh.eachAround(after, [&](std::int32_t slot, int) {
      for (int k = 0; k < 3; ++k) joined = joined || mesh.corner(slot, k) == before;
    });
    if (joined) return false;
    bool empty = true;
    forVerticesNear(v, after, before, [&](VertexId u) {
      if (u != v && u != after && u != before && !gone(u) && inTriangle(u, v, after, before)) empty = false;
    });
    return empty;
  }
  bool coversMissingCell(VertexId v, VertexId a, VertexId b) const;
  bool inTriangle(VertexId u, VertexId v, VertexId a, VertexId b) const;  // closed, in the TIN's x/y
  template <class Visit>
  void forVerticesNear(VertexId v, VertexId a, VertexId b, Visit visit) const {
    const TinVertex *p[3] = {&tin_->vertices[v], &tin_->vertices[a], &tin_->vertices[b]};
    const int r0 = std::max(0, std::min({p[0]->row, p[1]->row, p[2]->row}) - 1);
    const int r1 = std::min(dem_->height - 1, std::max({p[0]->row, p[1]->row, p[2]->row}) + 1);
    const int c0 = std::max(0, std::min({p[0]->col, p[1]->col, p[2]->col}) - 1);
    const int c1 = std::min(dem_->width - 1, std::max({p[0]->col, p[1]->col, p[2]->col}) + 1);
    for (int r = r0; r <= r1; ++r) {
      const auto end = rowCells_.begin() + rowStart_[r + 1];
      for (auto it = std::lower_bound(rowCells_.begin() + rowStart_[r], end, RowCell{c0, 0}); it != end && it->col <= c1; ++it)
        visit(it->vertex);
    }
  }
  // 1 when the star's centre lies inside the polygon its ring closes (the new outline
  // edge would run outside the TIN), 0 on that edge, -1 outside it.
  static int sideOfNewEdge(const Star& star);
  // Which straight edge of the raster the vertex's cell is on (0 top row, 1 bottom row,
  // 2 left column, 3 right column), or -1; a corner is on two and counts as none.
  int rasterEdge(VertexId v) const;
  double distance(VertexId u, VertexId a, VertexId b) const;

  const Tin* tin_ = nullptr;
  const Dem* dem_ = nullptr;
  std::vector<VertexId> before_, after_;  // by TIN id: level 0's outline neighbours
  // The vertices sampled in each row of the DEM, by column: a sixth of the memory of a
  // vertex id for every cell at the default 3 x 3 block.
  struct RowCell {
    std::int32_t col;
    VertexId vertex;
    bool operator<(const RowCell& o) const { return col < o.col || (col == o.col && vertex < o.vertex); }
  };
  std::vector<std::size_t> rowStart_;  // by row, and one past the last: where its cells start
  std::vector<RowCell> rowCells_;
};

}  // namespace tinlod
