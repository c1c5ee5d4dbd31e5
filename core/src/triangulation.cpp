// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/triangulation.h"

#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/spatial_sort.h>

#include <numeric>

#include "cgal_types.h"

namespace tinlod {
namespace {

std::vector<cgal::Point> toPoints(const std::vector<TinVertex>& vertices) {
  std::vector<cgal::Point> points;
  points.reserve(vertices.size());
  for (const TinVertex& v : vertices) points.emplace_back(v.x, v.y, v.z);
  return points;
}

}  // namespace

// Spatially sorted insertion with the previous vertex as hint, as CGAL's own bulk
// insertion does, but in our loop so that progress and cancellation reach the user.
std::vector<cgal::VertexHandle> cgal::insertVertices(cgal::Delaunay& dt, const std::vector<TinVertex>& vertices,
                                                     const ProgressRange& progress) {
  const std::vector<cgal::Point> points = toPoints(vertices);
  std::vector<cgal::VertexHandle> handles(points.size());
  progress.report(0, "Triangulating");
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  using Pmap = CGAL::Pointer_property_map<cgal::Point>::const_type;
  using SortTraits = CGAL::Spatial_sort_traits_adapter_2<cgal::Traits, Pmap>;
  CGAL::spatial_sort(order.begin(), order.end(), SortTraits(CGAL::make_property_map(points)));
  progress.report(0.1, "Triangulating");

  cgal::Delaunay::Face_handle hint;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t before = dt.number_of_vertices();
    cgal::Delaunay::Vertex_handle v = dt.insert(points[order[k]], hint);
    if (dt.number_of_vertices() > before) {
      v->info().id = static_cast<VertexId>(order[k]);
      handles[order[k]] = v;
    }
    hint = v->face();
    if ((k & 0xFFFF) == 0) progress.report(0.1 + 0.8 * double(k) / order.size(), "Triangulating");
  }
  return handles;
}

Triangulation delaunayTriangles(const std::vector<TinVertex>& vertices, const ProgressRange& progress) {
  cgal::Delaunay dt;
  cgal::insertVertices(dt, vertices, progress);
  Triangulation out;
  out.triangles.reserve(dt.number_of_faces());
  for (auto f = dt.all_faces_begin(); f != dt.all_faces_end(); ++f) f->info().id = kNoNeighbour;
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    f->info().id = static_cast<std::int32_t>(out.triangles.size());
    out.triangles.push_back({f->vertex(0)->info().id, f->vertex(1)->info().id, f->vertex(2)->info().id});
  }
  out.neighbours.reserve(out.triangles.size());
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
    out.neighbours.push_back({f->neighbor(0)->info().id, f->neighbor(1)->info().id, f->neighbor(2)->info().id});
  progress.report(1.0, "Triangulating");
  return out;
}

}  // namespace tinlod
