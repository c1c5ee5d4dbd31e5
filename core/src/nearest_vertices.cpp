// SPDX-License-Identifier: GPL-3.0-or-later
#include "nearest_vertices.h"

#include <algorithm>

#include "box_grid.h"
#include "cgal_types.h"
#include "triangle_contains.h"

namespace tinlod {
namespace {

bool onTriangle(const Tin& tin, const Triangle& t, const ExactPoint2& p) {
  const TinVertex &a = tin.vertices[t[0]], &b = tin.vertices[t[1]], &c = tin.vertices[t[2]];
  return triangleContains({a.x, a.y}, {b.x, b.y}, {c.x, c.y}, p);
}

BoxGrid triangleGrid(const Tin& tin) {
  std::vector<Box> boxes;
  boxes.reserve(tin.triangles.size());
  for (const Triangle& t : tin.triangles) {
    const TinVertex &a = tin.vertices[t[0]], &b = tin.vertices[t[1]], &c = tin.vertices[t[2]];
    boxes.push_back({std::min({a.x, b.x, c.x}), std::min({a.y, b.y, c.y}), std::max({a.x, b.x, c.x}),
                     std::max({a.y, b.y, c.y})});
  }
  return BoxGrid(boxes);
}

}  // namespace

// The triangles say whether a point is on the data; the Delaunay triangulation of all
// the vertices finds the nearest one, which may lie across a hole.
std::vector<VertexId> nearestVerticesOnData(const Tin& tin, const std::vector<std::array<double, 2>>& points,
                                            std::size_t& off, const ProgressRange& progress,
                                            const std::vector<std::uint8_t>& excluded) {
  off = 0;
  std::vector<VertexId> nearest;
  if (points.empty()) return nearest;
  const BoxGrid grid = triangleGrid(tin);
  // The allowed vertices are copied only when some are left out (a tile's lines): the
  // whole TIN's would be a second copy of every vertex.
  std::vector<TinVertex> allowed;
  std::vector<VertexId> idOf;  // of each allowed vertex, in the TIN
  if (!excluded.empty())
    for (VertexId v = 0; v < tin.vertices.size(); ++v)
      if (!excluded[v]) allowed.push_back(tin.vertices[v]), idOf.push_back(v);
  cgal::Delaunay dt;
  cgal::insertVertices(dt, excluded.empty() ? tin.vertices : allowed, progress);
  cgal::FaceHandle hint;
  for (const auto& p : points) {
    const cgal::Point q(p[0], p[1], 0);
    const auto [first, last] = grid.at(p[0], p[1]);
    if (std::none_of(first, last, [&](std::uint32_t t) { return onTriangle(tin, tin.triangles[t], {p[0], p[1]}); })) {
      ++off;
      continue;
    }
    if (dt.number_of_vertices() == 0) continue;  // nothing it may hold
    hint = dt.locate(q, hint);
    const VertexId v = dt.nearest_vertex(q, hint)->info().id;
    nearest.push_back(excluded.empty() ? v : idOf[v]);
  }
  return nearest;
}

}  // namespace tinlod
