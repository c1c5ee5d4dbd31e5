// SPDX-License-Identifier: GPL-3.0-or-later
// The cell scan takes every cell centre under a triangulation exactly once, whatever lies
// on an edge or a vertex: the figures of a level count each valid cell once.
#include <gtest/gtest.h>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cmath>
#include <random>
#include <vector>

#include "cell_scan.h"

namespace tinlod {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<VertexId, K>;
using Dt = CGAL::Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<Vb>>;

// Points in a 40 x 30 grid: the four corners, points on whole rows and columns (edges then
// run through cell centres), points exactly on cell centres, and points anywhere.
std::vector<std::pair<K::Point_2, VertexId>> points(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> c(0, 39), r(0, 29);
  std::uniform_int_distribution<int> ci(0, 39), ri(0, 29);
  std::vector<std::pair<K::Point_2, VertexId>> out = {{{0, 0}, 0}, {{39, 0}, 1}, {{0, 29}, 2}, {{39, 29}, 3}};
  for (int i = 0; i < 60; ++i) {
    const VertexId id = VertexId(out.size());
    switch (i % 4) {
      case 0: out.push_back({{double(ci(rng)), double(ri(rng))}, id}); break;  // on a centre
      case 1: out.push_back({{c(rng), double(ri(rng))}, id}); break;           // on a row
      case 2: out.push_back({{double(ci(rng)), r(rng)}, id}); break;           // on a column
      default: out.push_back({{c(rng), r(rng)}, id});
    }
  }
  return out;
}

TEST(CellScan, EveryCentreUnderATriangulationIsTakenOnce) {
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const auto pts = points(seed);
    Dt dt(pts.begin(), pts.end());
    std::vector<int> taken(40 * 30, 0);
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
      CellCorner p[3];
      bool outline[3];
      for (int k = 0; k < 3; ++k) {
        const auto v = f->vertex(k);
        p[k] = {v->point().x(), v->point().y(), 0.0, v->info()};
        outline[k] = dt.is_infinite(f->neighbor(k));  // the edge opposite corner k is on the hull
      }
      scanCells(40, 30, p, outline, [&](int row, int col, double) { ++taken[row * 40 + col]; });
    }
    // The hull is the 40 x 30 rectangle of centres (0..39, 0..29): every centre once, but a
    // centre that is exactly a vertex on the hull, which both hull triangles there may take
    // (a raster corner, whose vertex is the cell itself: at distance 0).
    std::vector<int> hullVertex(40 * 30, 0);
    for (const auto& [p, id] : pts)
      if ((p.x() == 0 || p.x() == 39 || p.y() == 0 || p.y() == 29) && p.x() == std::floor(p.x()) && p.y() == std::floor(p.y()))
        hullVertex[int(p.y()) * 40 + int(p.x())] = 1;
    for (int row = 0; row < 30; ++row)
      for (int col = 0; col < 40; ++col) {
        const int n = taken[row * 40 + col];
        ASSERT_GE(n, 1) << "cell " << row << ", " << col;
        if (!hullVertex[row * 40 + col]) ASSERT_EQ(n, 1) << "cell " << row << ", " << col;
        else ASSERT_LE(n, 2) << "cell " << row << ", " << col;
      }
  }
}

// Heights are the plane through the corners: exact at a corner, linear between.
TEST(CellScan, HeightsAreThePlaneThroughTheCorners) {
  const CellCorner p[3] = {{2, 1, 10, 0}, {12, 3, 30, 1}, {4, 11, -5, 2}};
  const bool outline[3] = {true, true, true};
  auto plane = [](double c, double r) {  // through the three corners, solved by hand
    const double d = (12 - 2) * (11 - 1) - (4 - 2) * (3 - 1);
    const double dzdc = ((30 - 10) * (11 - 1) - (-5 - 10) * (3 - 1)) / d;
    const double dzdr = ((-5 - 10) * (12 - 2) - (30 - 10) * (4 - 2)) / d;
    return 10 + dzdc * (c - 2) + dzdr * (r - 1);
  };
  int cells = 0;
  scanCells(20, 20, p, outline, [&](int row, int col, double z) {
    EXPECT_NEAR(z, plane(col, row), 1e-9);
    ++cells;
  });
  EXPECT_GT(cells, 40);
  int corner = 0;
  scanCells(20, 20, p, outline, [&](int row, int col, double z) {
    if (row == 1 && col == 2) {
      EXPECT_EQ(z, 10.0);
      ++corner;
    }
  });
  EXPECT_EQ(corner, 1);
}

}  // namespace
}  // namespace tinlod
