// SPDX-License-Identifier: GPL-3.0-or-later
// Private: when an outline vertex may go. Deleting it joins its two outline neighbours
// by a straight edge; the outline vertices of level 0 that edge replaces (the vertex and
// those deleted between the neighbours before it) must all lie within the tolerance of it,
// so the outline never moves further than that from the data's own. The new edge may cut
// into the data (the cells it gives up are counted) but never out over nodata: a vertex
// whose new edge would pass outside the TIN goes only along one straight raster edge (a
// DEM in degrees bends it by millimetres in the TIN's metric CRS), where no cell lies
// beyond.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "simplification_mesh.h"
#include "tinlod/tin.h"

namespace tinlod {

class OutlineChain {
 public:
  OutlineChain() = default;
  // Level 0's outline order, for the open vertices of one fan; `width` x `height` is the
  // DEM's grid, whose edges the vertices' rows and columns are compared with.
  OutlineChain(const SimplificationMesh& mesh, const Tin& tin, int width, int height);

  // A corner of the raster: it stays, so a rectangular DEM keeps its rectangle.
  bool rasterCorner(VertexId v) const;
  // Whether open vertex v, whose open star's ring is `star` (its first ring vertex the
  // outline neighbour after it, its last the one before), may go with the outline moved
  // by at most `tolerance` metres from level 0's; where the new edge would run outside
  // the TIN (along a raster edge), by at most `outward` metres, so that the TIN stays on
  // the raster (half a cell beyond the edge's centres).
  bool allows(VertexId v, const Star& star, VertexId after, VertexId before, double tolerance, double outward) const {
    if (!oneSide(v, star, after, before)) return false;
    if (sideOfNewEdge(star) > 0) tolerance = std::min(tolerance, outward);
    bool within = distance(v, after, before) <= tolerance;
    for (VertexId u = before_[v]; within && u != before; u = before_[u]) within = distance(u, after, before) <= tolerance;
    for (VertexId u = after_[v]; within && u != after; u = after_[u]) within = distance(u, after, before) <= tolerance;
    return within;
  }

 private:
  bool oneSide(VertexId v, const Star& star, VertexId after, VertexId before) const {
    const int side = sideOfNewEdge(star);
    if (side <= 0) return true;  // on or inside the TIN: the new edge cuts into the data or runs along it
    const int edge = rasterEdge(v);
    if (edge < 0 || rasterEdge(after) != edge || rasterEdge(before) != edge) return false;
    for (VertexId u = before_[v]; u != before; u = before_[u])
      if (rasterEdge(u) != edge) return false;
    for (VertexId u = after_[v]; u != after; u = after_[u])
      if (rasterEdge(u) != edge) return false;
    return true;
  }
  // 1 when the star's centre lies inside the polygon its ring closes (the new outline
  // edge would run outside the TIN), 0 on that edge, -1 outside it.
  static int sideOfNewEdge(const Star& star);
  // Which straight edge of the raster the vertex's cell is on (0 top row, 1 bottom row,
  // 2 left column, 3 right column), or -1; a corner is on two and counts as none.
  int rasterEdge(VertexId v) const;
  double distance(VertexId u, VertexId a, VertexId b) const;

  const Tin* tin_ = nullptr;
  int width_ = 0, height_ = 0;
  std::vector<VertexId> before_, after_;  // by TIN id: level 0's outline neighbours
};

}  // namespace tinlod
