// SPDX-License-Identifier: GPL-3.0-or-later
#include "outline_chain.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>

namespace tinlod {

OutlineChain::OutlineChain(const SimplificationMesh& mesh, const Tin& tin, int width, int height)
    : tin_(&tin), width_(width), height_(height), before_(tin.vertices.size()), after_(tin.vertices.size()) {
  for (VertexId v = 0; v < tin.vertices.size(); ++v)
    if (mesh.deletableOpen(v)) before_[v] = mesh.outlineBefore(v), after_[v] = mesh.outlineAfter(v);
}

bool OutlineChain::rasterCorner(VertexId v) const {
  const TinVertex& p = tin_->vertices[v];
  return (p.row == 0 || p.row == height_ - 1) && (p.col == 0 || p.col == width_ - 1);
}

int OutlineChain::rasterEdge(VertexId v) const {
  const TinVertex& p = tin_->vertices[v];
  const int edges = (p.row == 0) + (p.row == height_ - 1) + (p.col == 0) + (p.col == width_ - 1);
  if (edges != 1) return -1;
  return p.row == 0 ? 0 : p.row == height_ - 1 ? 1 : p.col == 0 ? 2 : 3;
}

int OutlineChain::sideOfNewEdge(const Star& star) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
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
