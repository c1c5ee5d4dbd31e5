// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "tinlod/importance.h"
#include "tinlod/triangle_plane.h"

namespace tinlod {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Dt = CGAL::Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<Vb>>;

// A regular polygon of n vertices of radius r on the plane z = 0, around a centre at
// height h: a pyramid.
Star pyramid(int n, double r, double h) {
  Star s;
  s.centre = {0, 0, h};
  for (int i = 0; i < n; ++i) s.ring.push_back({r * std::cos(2 * M_PI * i / n), r * std::sin(2 * M_PI * i / n), 0});
  return s;
}

TEST(Importance, RetriangulationIsCgalsDelaunayRemoval) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 100);
  int compared = 0;
  for (int trial = 0; trial < 40; ++trial) {
    Dt dt;
    std::vector<std::pair<K::Point_2, int>> points;
    for (int i = 0; i < 200; ++i) points.push_back({K::Point_2(u(rng), u(rng)), i});
    dt.insert(points.begin(), points.end());
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
      bool onHull = false;
      auto f = dt.incident_faces(v), fd = f;
      do onHull = onHull || dt.is_infinite(f);
      while (++f != fd);
      if (onHull || compared > 400 * (trial + 1) / 40) continue;
      // The star, and what CGAL makes of it when the centre is removed.
      Star star;
      star.centre = {v->point().x(), v->point().y(), 0};
      std::vector<int> ids;
      auto n = dt.incident_vertices(v), nd = n;
      do {
        star.ring.push_back({n->point().x(), n->point().y(), 0});
        ids.push_back(n->info());
      } while (++n != nd);
      std::set<std::set<int>> mine;
      for (const LocalTriangle& t : retriangulateStar(star)) mine.insert({ids[t[0]], ids[t[1]], ids[t[2]]});
      Dt copy;
      std::vector<std::pair<K::Point_2, int>> others;
      for (auto w = dt.finite_vertices_begin(); w != dt.finite_vertices_end(); ++w)
        if (w != v) others.push_back({w->point(), w->info()});
      copy.insert(others.begin(), others.end());
      // CGAL's new faces are those whose centroid lies in the old star's fan.
      auto inStar = [&](const K::Point_2& c) {
        for (std::size_t i = 0; i < star.ring.size(); ++i) {
          const Point3 &a = star.ring[i], &b = star.ring[(i + 1) % star.ring.size()];
          const K::Point_2 pa(a.x, a.y), pb(b.x, b.y);
          if (CGAL::orientation(v->point(), pa, c) != CGAL::RIGHT_TURN && CGAL::orientation(pa, pb, c) != CGAL::RIGHT_TURN &&
              CGAL::orientation(pb, v->point(), c) != CGAL::RIGHT_TURN)
            return true;
        }
        return false;
      };
      std::set<std::set<int>> cgal;
      for (auto g = copy.finite_faces_begin(); g != copy.finite_faces_end(); ++g)
        if (inStar(CGAL::centroid(g->vertex(0)->point(), g->vertex(1)->point(), g->vertex(2)->point())))
          cgal.insert({g->vertex(0)->info(), g->vertex(1)->info(), g->vertex(2)->info()});
      ASSERT_EQ(mine.size(), star.ring.size() - 2);
      ASSERT_EQ(cgal, mine) << "star of degree " << star.ring.size();
      ++compared;
    }
  }
  EXPECT_GT(compared, 300);
}

TEST(Importance, PlaneAndPyramidVolumes) {
  EXPECT_NEAR(volumeChange(pyramid(6, 10, 0), retriangulateStar(pyramid(6, 10, 0))), 0, 1e-9);
  // A cone of height h over a polygon of area A: volume A h / 3.
  const Star p = pyramid(8, 10, 3);
  const double area = 0.5 * 8 * 100 * std::sin(2 * M_PI / 8);
  EXPECT_NEAR(volumeChange(p, retriangulateStar(p)), area * 3 / 3, 1e-9);
  EXPECT_NEAR(importance(Measure::Volume, p), area * 3 / 3, 1e-9);  // the simplifier's floating-point queue
  EXPECT_NEAR(importance(Measure::Volume, pyramid(6, 10, 0)), 0, 1e-9);
}

TEST(Importance, FlatnessIsOneOnAPlaneAndCosOfTheSlopeOnAPyramid) {
  EXPECT_NEAR(normalFlatness(pyramid(7, 5, 0)), 1.0, 1e-12);
  // Each face of a regular pyramid leans by atan(h / apothem); the mean normal is vertical.
  const int n = 6;
  const double r = 10, h = 4, apothem = r * std::cos(M_PI / n);
  EXPECT_NEAR(normalFlatness(pyramid(n, r, h)), std::cos(std::atan(h / apothem)), 1e-12);
  Star tilted = pyramid(5, 10, 0);  // a tilted plane is still flat
  for (Point3& q : tilted.ring) q.z = 0.3 * q.x + 0.2 * q.y;
  EXPECT_NEAR(normalFlatness(tilted), 1.0, 1e-12);
  EXPECT_NEAR(importance(Measure::Normal, tilted), 0.0, 1e-12);
}

// Twelve points with whole coordinates exactly on the circle of radius 5: every
// triangulation of the polygon is Delaunay, so floating-point ranking of ears is all
// ties. The result must still be a triangulation with no vertex strictly inside any
// triangle's circumcircle (exact test).
TEST(Importance, RetriangulationOfAnExactlyCocircularStar) {
  Star s;
  s.centre = {0.5, 0.25, 1};
  for (auto [x, y] : std::vector<std::pair<double, double>>{{5, 0}, {4, 3}, {3, 4}, {0, 5}, {-3, 4}, {-4, 3},
                                                             {-5, 0}, {-4, -3}, {-3, -4}, {0, -5}, {3, -4}, {4, -3}})
    s.ring.push_back({x, y, 0});
  const std::vector<LocalTriangle> tris = retriangulateStar(s);
  ASSERT_EQ(tris.size(), 10u);
  double area = 0, polygon = 0;
  for (std::size_t i = 0; i < s.ring.size(); ++i) {
    const Point3 &a = s.ring[i], &b = s.ring[(i + 1) % s.ring.size()];
    polygon += 0.5 * (a.x * b.y - b.x * a.y);
  }
  for (const LocalTriangle& t : tris) {
    const K::Point_2 a(s.ring[t[0]].x, s.ring[t[0]].y), b(s.ring[t[1]].x, s.ring[t[1]].y), c(s.ring[t[2]].x, s.ring[t[2]].y);
    ASSERT_EQ(CGAL::orientation(a, b, c), CGAL::LEFT_TURN);
    area += CGAL::area(a, b, c);
    for (const Point3& q : s.ring)
      EXPECT_NE(CGAL::side_of_oriented_circle(a, b, c, K::Point_2(q.x, q.y)), CGAL::ON_POSITIVE_SIDE);
  }
  EXPECT_DOUBLE_EQ(area, polygon);
}

TEST(Importance, DegreeIsTheRingSize) {
  EXPECT_EQ(importance(Measure::Degree, pyramid(6, 10, 2.5)), 6.0);
  Star open = pyramid(6, 10, 2.5);
  open.open = true;
  EXPECT_EQ(importance(Measure::Degree, open), 6.0);
}

// A triangle's plane, from UTM-sized coordinates, gives the heights of the plane through
// its corners: z = 7 + 0.2 (x - x0) - 0.35 (y - y0).
TEST(Importance, TrianglePlaneHeights) {
  const double x0 = 512345.25, y0 = 5123456.75;
  auto z = [&](double x, double y) { return 7 + 0.2 * (x - x0) - 0.35 * (y - y0); };
  Star s;
  s.ring = {{x0, y0, z(x0, y0)}, {x0 + 90, y0 + 5, z(x0 + 90, y0 + 5)}, {x0 + 20, y0 + 80, z(x0 + 20, y0 + 80)}};
  const TrianglePlane plane =
      TrianglePlane::through(s.ring[0].x, s.ring[0].y, s.ring[0].z, s.ring[1].x, s.ring[1].y, s.ring[1].z, s.ring[2].x,
                             s.ring[2].y, s.ring[2].z);
  for (double dx : {0.0, 13.5, 40.0})
    for (double dy : {0.0, 7.25, 30.0}) EXPECT_NEAR(plane.height(x0 + dx, y0 + dy), z(x0 + dx, y0 + dy), 1e-9);
}

// An outline vertex on a straight edge of the TIN (the line y = 0, as the sampler places a
// raster edge's cells): its open star filled as CGAL's own removal of that hull vertex
// fills it. The study's perturbation of every other point makes the answer unique.
TEST(Importance, OpenStarFillIsCgalsRemovalOfACollinearHullVertex) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 100), h(1, 100);
  int compared = 0;
  for (int trial = 0; trial < 30; ++trial) {
    Dt dt;
    std::vector<std::pair<K::Point_2, int>> points;
    for (int i = 0; i < 150; ++i) points.push_back({K::Point_2(u(rng), h(rng)), i});
    for (int i = 0; i <= 20; ++i) points.push_back({K::Point_2(5.0 * i + 0.37 * (i % 3), 0), 1000 + i});
    dt.insert(points.begin(), points.end());
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
      if (v->info() <= 1000 || v->info() >= 1020) continue;  // the inner points of the edge
      // The ring from the edge neighbour after v (counter-clockwise, interior on the left:
      // towards +x) round to the one before it.
      std::vector<Dt::Vertex_handle> around;
      auto n = dt.incident_vertices(v), nd = n;
      do around.push_back(n);
      while (++n != nd);
      auto after = std::find_if(around.begin(), around.end(), [&](Dt::Vertex_handle w) {
        return !dt.is_infinite(w) && w->info() == v->info() + 1;
      });
      ASSERT_NE(after, around.end());
      std::rotate(around.begin(), after, around.end());
      Star star;
      star.open = true;
      star.centre = {v->point().x(), v->point().y(), 0};
      std::vector<int> ids;
      for (Dt::Vertex_handle w : around) {
        if (dt.is_infinite(w)) continue;
        star.ring.push_back({w->point().x(), w->point().y(), 0});
        ids.push_back(w->info());
      }
      ASSERT_EQ(ids.back(), v->info() - 1);
      std::vector<LocalTriangle> fill;
      ASSERT_TRUE(retriangulateStar(star, fill));
      ASSERT_EQ(fill.size() + 2, star.ring.size());
      std::set<std::set<int>> mine;
      for (const LocalTriangle& t : fill) {
        EXPECT_EQ(CGAL::orientation(K::Point_2(star.ring[t[0]].x, star.ring[t[0]].y), K::Point_2(star.ring[t[1]].x, star.ring[t[1]].y),
                                    K::Point_2(star.ring[t[2]].x, star.ring[t[2]].y)),
                  CGAL::LEFT_TURN);
        mine.insert({ids[t[0]], ids[t[1]], ids[t[2]]});
      }
      std::set<int> ringIds(ids.begin(), ids.end());
      Dt copy;
      std::vector<std::pair<K::Point_2, int>> others;
      for (auto w = dt.finite_vertices_begin(); w != dt.finite_vertices_end(); ++w)
        if (w != v) others.push_back({w->point(), w->info()});
      copy.insert(others.begin(), others.end());
      std::set<std::set<int>> cgal;  // CGAL's faces made only of ring vertices
      for (auto g = copy.finite_faces_begin(); g != copy.finite_faces_end(); ++g) {
        const std::set<int> f{g->vertex(0)->info(), g->vertex(1)->info(), g->vertex(2)->info()};
        if (std::all_of(f.begin(), f.end(), [&](int i) { return ringIds.count(i) > 0; })) cgal.insert(f);
      }
      for (const auto& t : mine) EXPECT_TRUE(cgal.count(t)) << "a fill triangle CGAL does not make";
      ++compared;
    }
  }
  EXPECT_GT(compared, 400);
}

// The new outline edge must leave every other ring vertex strictly inside: otherwise the
// polygon is not simple and nothing is filled.
TEST(Importance, OpenStarWhoseNewEdgeCrossesItsRingIsRefused) {
  Star star;
  star.open = true;
  star.centre = {0, 0, 0};
  star.ring = {{10, 0, 0}, {5, 5, 0}, {0, -1, 0}, {-5, 5, 0}, {-10, 0, 0}};  // (0, -1) lies beyond the edge
  std::vector<LocalTriangle> fill;
  EXPECT_FALSE(retriangulateStar(star, fill));
  EXPECT_TRUE(fill.empty());
  EXPECT_EQ(importance(Measure::Volume, star), INFINITY);
  star.ring[2] = {0, 1, 0};
  EXPECT_TRUE(retriangulateStar(star, fill));
  EXPECT_EQ(fill.size(), 3u);
}

// An outline vertex raised above a straight edge: the volume it changes over the ground
// both surfaces cover is that of the pyramid it tops (no ground is given up on a line).
TEST(Importance, OpenStarVolumeOnAStraightEdge) {
  Star star;
  star.open = true;
  star.centre = {0, 0, 6};
  star.ring = {{10, 0, 0}, {0, 10, 0}, {-10, 0, 0}};
  // Two triangles of area 50 under a cone of height 6 at one corner: 2 * 50 * 6 / 3.
  EXPECT_NEAR(importance(Measure::Volume, star), 200.0, 1e-9);
  star.centre.z = 0;
  EXPECT_NEAR(importance(Measure::Volume, star), 0.0, 1e-9);
  EXPECT_NEAR(normalFlatness(star), 1.0, 1e-12);
}

}  // namespace
}  // namespace tinlod
