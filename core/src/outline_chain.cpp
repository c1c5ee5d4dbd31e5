// SPDX-License-Identifier: GPL-3.0-or-later
#include "outline_chain.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>

#include "triangle_contains.h"

namespace tinlod {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

// Whether q lies in the closed triangle a, b, c of either orientation (the grid's rows run
// against the TIN's y); a degenerate one holds nothing.
bool inClosed(const K::Point_2& a, const K::Point_2& b, const K::Point_2& c, const K::Point_2& q) {
  switch (CGAL::orientation(a, b, c)) {
    case CGAL::LEFT_TURN: return triangleContains(a, b, c, q);
    case CGAL::RIGHT_TURN: return triangleContains(a, c, b, q);
    default: return false;
  }
}

}  // namespace

OutlineChain::OutlineChain(const SimplificationMesh& mesh, const Tin& tin, const Dem& dem)
    : tin_(&tin), dem_(&dem), before_(tin.vertices.size()), after_(tin.vertices.size()),
      rowStart_(static_cast<std::size_t>(dem.height) + 1, 0) {
  auto onDem = [&](const TinVertex& p) { return p.row >= 0 && p.col >= 0 && p.row < dem.height && p.col < dem.width; };
  for (VertexId v = 0; v < tin.vertices.size(); ++v) {
    if (mesh.deletableOpen(v)) before_[v] = mesh.outlineBefore(v), after_[v] = mesh.outlineAfter(v);
    if (onDem(tin.vertices[v])) ++rowStart_[tin.vertices[v].row + 1];
  }
  for (std::size_t r = 1; r < rowStart_.size(); ++r) rowStart_[r] += rowStart_[r - 1];
  rowCells_.resize(rowStart_.back());
  std::vector<std::size_t> next(rowStart_.begin(), rowStart_.end() - 1);
  for (VertexId v = 0; v < tin.vertices.size(); ++v)
    if (const TinVertex& p = tin.vertices[v]; onDem(p)) rowCells_[next[p.row]++] = {p.col, v};
  for (int r = 0; r < dem.height; ++r) std::sort(rowCells_.begin() + rowStart_[r], rowCells_.begin() + rowStart_[r + 1]);
}

bool OutlineChain::rasterCorner(VertexId v) const {
  const TinVertex& p = tin_->vertices[v];
  return (p.row == 0 || p.row == dem_->height - 1) && (p.col == 0 || p.col == dem_->width - 1);
}

int OutlineChain::rasterEdge(VertexId v) const {
  const TinVertex& p = tin_->vertices[v];
  const int last = dem_->height - 1, right = dem_->width - 1;
  const int edges = (p.row == 0) + (p.row == last) + (p.col == 0) + (p.col == right);
  if (edges != 1) return -1;
  return p.row == 0 ? 0 : p.row == last ? 1 : p.col == 0 ? 2 : 3;
}

bool OutlineChain::onOneRasterEdge(VertexId v, VertexId after, VertexId before) const {
  const int edge = rasterEdge(v);
  if (edge < 0 || rasterEdge(after) != edge || rasterEdge(before) != edge) return false;
  for (VertexId u = before_[v]; u != before; u = before_[u])
    if (rasterEdge(u) != edge) return false;
  for (VertexId u = after_[v]; u != after; u = after_[u])
    if (rasterEdge(u) != edge) return false;
  return true;
}

bool OutlineChain::alongOneRasterEdge(VertexId v, VertexId after, VertexId before) const {
  const int edge = rasterEdge(v);
  const int last = dem_->height - 1, right = dem_->width - 1;
  const auto onLine = [&](VertexId u) {
    const TinVertex& p = tin_->vertices[u];
    return edge == 0 ? p.row == 0 : edge == 1 ? p.row == last : edge == 2 ? p.col == 0 : p.col == right;
  };
  return edge >= 0 && onLine(after) && onLine(before);
}

// Every lattice point of the grid in the closed triangle, with its corners where the
// jitter put them and at their cells' centres: a missing or off-raster cell there would
// be covered.
bool OutlineChain::coversMissingCell(VertexId v, VertexId a, VertexId b) const {
  const TinVertex* p[3] = {&tin_->vertices[v], &tin_->vertices[a], &tin_->vertices[b]};
  K::Point_2 jittered[3], centred[3];
  double r0 = INFINITY, r1 = -INFINITY, c0 = INFINITY, c1 = -INFINITY;
  for (int k = 0; k < 3; ++k) {
    const double c = p[k]->col + double(p[k]->dcol), r = p[k]->row + double(p[k]->drow);
    jittered[k] = K::Point_2(c, r), centred[k] = K::Point_2(p[k]->col, p[k]->row);
    r0 = std::min({r0, r, double(p[k]->row)}), r1 = std::max({r1, r, double(p[k]->row)});
    c0 = std::min({c0, c, double(p[k]->col)}), c1 = std::max({c1, c, double(p[k]->col)});
  }
  for (int r = static_cast<int>(std::floor(r0)); r <= static_cast<int>(std::ceil(r1)); ++r)
    for (int c = static_cast<int>(std::floor(c0)); c <= static_cast<int>(std::ceil(c1)); ++c) {
      if (dem_->valid(r, c)) continue;
      const K::Point_2 q(c, r);
      if (inClosed(jittered[0], jittered[1], jittered[2], q) || inClosed(centred[0], centred[1], centred[2], q)) return true;
    }
  return false;
}

bool OutlineChain::inTriangle(VertexId u, VertexId v, VertexId a, VertexId b) const {
  const auto xy = [&](VertexId w) { return K::Point_2(tin_->vertices[w].x, tin_->vertices[w].y); };
  return inClosed(xy(v), xy(a), xy(b), xy(u));
}

int OutlineChain::sideOfNewEdge(const Star& star) {
  const Point3 &from = star.ring.back(), &to = star.ring.front(), &c = star.centre;
  switch (CGAL::orientation(K::Point_2(from.x, from.y), K::Point_2(to.x, to.y), K::Point_2(c.x, c.y))) {
    case CGAL::LEFT_TURN: return 1;
    case CGAL::RIGHT_TURN: return -1;
    default: return 0;
  }
}

// From u to the segment a-b, in the TIN's metres.
double OutlineChain::distance(VertexId u, VertexId a, VertexId b) const {
  const TinVertex &p = tin_->vertices[u], &s = tin_->vertices[a], &e = tin_->vertices[b];
  const double dx = e.x - s.x, dy = e.y - s.y, len2 = dx * dx + dy * dy;
  const double t = len2 > 0 ? std::clamp(((p.x - s.x) * dx + (p.y - s.y) * dy) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(p.x - (s.x + t * dx), p.y - (s.y + t * dy));
}

}  // namespace tinlod
