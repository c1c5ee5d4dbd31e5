// SPDX-License-Identifier: GPL-3.0-or-later
// CGAL's own Delaunay remove() rate on a TIN, the yardstick of the build benchmark:
// independent sets of interior vertices, picked in a pass and then removed, until as
// many vertices as the build removed are gone. Only remove() is timed.
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Projection_traits_xy_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <chrono>
#include <vector>

#include "tinlod/tin.h"

double bareRemoveRate(const tinlod::Tin& tin, std::size_t count) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Gt = CGAL::Projection_traits_xy_3<K>;
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, Gt>;
  using Dt = CGAL::Delaunay_triangulation_2<Gt, CGAL::Triangulation_data_structure_2<Vb>>;
  std::vector<std::pair<K::Point_3, int>> points;
  for (const tinlod::TinVertex& v : tin.vertices) points.push_back({K::Point_3(v.x, v.y, v.z), -1});
  Dt dt(points.begin(), points.end());
  std::size_t removed = 0;
  double seconds = 0;
  for (int round = 0; removed < count; ++round) {
    std::vector<Dt::Vertex_handle> batch;
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end() && removed + batch.size() < count; ++v) {
      if (v->info() == round) continue;  // a neighbour of a vertex already picked
      bool interior = true;
      auto f = dt.incident_faces(v), fd = f;
      do interior = interior && !dt.is_infinite(f);
      while (++f != fd);
      if (!interior) continue;
      batch.push_back(v);
      v->info() = round;
      auto n = dt.incident_vertices(v), nd = n;
      do n->info() = round;
      while (++n != nd);
    }
    if (batch.empty()) break;
    const auto t0 = std::chrono::steady_clock::now();
    for (Dt::Vertex_handle v : batch) dt.remove(v);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    removed += batch.size();
  }
  return removed / seconds / 1e6;
}
