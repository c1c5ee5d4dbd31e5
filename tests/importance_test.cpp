// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cmath>
#include <random>
#include <set>

#include "tinlod/importance.h"

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
  EXPECT_NEAR(importance(Measure::Volume, p, {}), area * 3 / 3, 1e-9);  // the simplifier's floating-point queue
  EXPECT_NEAR(importance(Measure::Volume, pyramid(6, 10, 0), {}), 0, 1e-9);
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
  EXPECT_NEAR(importance(Measure::Normal, tilted, {}), 0.0, 1e-12);
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

TEST(Importance, VerticalErrorOfTheCentreAndOfSamples) {
  const Star p = pyramid(6, 10, 2.5);
  const auto tris = retriangulateStar(p);
  EXPECT_NEAR(maxVerticalError(p, tris, {}), 2.5, 1e-12);
  EXPECT_NEAR(maxVerticalError(p, tris, {{1, 1, -4}}), 4.0, 1e-12);
  EXPECT_EQ(importance(Measure::Degree, p, {}), 6.0);
}

// A triangle's plane, from UTM-sized coordinates, gives the heights of the plane through
// its corners: z = 7 + 0.2 (x - x0) - 0.35 (y - y0).
TEST(Importance, TrianglePlaneHeights) {
  const double x0 = 512345.25, y0 = 5123456.75;
  auto z = [&](double x, double y) { return 7 + 0.2 * (x - x0) - 0.35 * (y - y0); };
  Star s;
  s.ring = {{x0, y0, z(x0, y0)}, {x0 + 90, y0 + 5, z(x0 + 90, y0 + 5)}, {x0 + 20, y0 + 80, z(x0 + 20, y0 + 80)}};
  const TrianglePlane plane = planeOf(s, {0, 1, 2});
  for (double dx : {0.0, 13.5, 40.0})
    for (double dy : {0.0, 7.25, 30.0}) EXPECT_NEAR(plane.height(x0 + dx, y0 + dy), z(x0 + dx, y0 + dy), 1e-9);
}

// triangleHolding takes the last triangle without a test, and tests only the diagonals
// of a convex polygon, since the points it is given lie in the star's polygon: it must
// still name the likely triangle when that holds the point, else the first triangle
// that holds it, corners and shared edges included, in convex and bent stars alike
// (dropping the convexity condition fails).
TEST(Importance, TriangleHoldingIsTheLikelyOrTheFirstTriangleThatHoldsThePoint) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 100), w(0, 1);
  Dt dt;
  std::vector<std::pair<K::Point_2, int>> points;
  for (int i = 0; i < 300; ++i) points.push_back({K::Point_2(u(rng), u(rng)), i});
  dt.insert(points.begin(), points.end());
  auto xy = [](const Point3& p) { return K::Point_2(p.x, p.y); };
  int checked = 0;
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
    Star star;
    star.centre = {v->point().x(), v->point().y(), 0};
    bool onHull = false;
    auto n = dt.incident_vertices(v), nd = n;
    do {
      onHull = onHull || dt.is_infinite(n);
      star.ring.push_back({n->point().x(), n->point().y(), 0});
    } while (++n != nd);
    if (onHull) continue;
    std::vector<LocalTriangle> fill;
    ASSERT_EQ(retriangulateStar(star, fill), convexRing(star));  // the queue's own finding
    std::vector<Point3> probes{star.centre};
    const std::size_t d = star.ring.size();
    for (std::size_t i = 0; i < d; ++i) {
      const Point3 &a = star.ring[i], &b = star.ring[(i + 1) % d];
      probes.push_back(a);
      probes.push_back({(a.x + b.x) / 2, (a.y + b.y) / 2, 0});
      for (int k = 0; k < 4; ++k) {  // inside the old star's triangle centre, a, b
        double s = w(rng), t = w(rng);
        if (s + t > 1) s = 1 - s, t = 1 - t;
        probes.push_back({star.centre.x + s * (a.x - star.centre.x) + t * (b.x - star.centre.x),
                          star.centre.y + s * (a.y - star.centre.y) + t * (b.y - star.centre.y), 0});
      }
    }
    for (const LocalTriangle& t : fill)  // on the diagonals
      for (int e = 0; e < 3; ++e) {
        const Point3 &a = star.ring[t[e]], &b = star.ring[t[(e + 1) % 3]];
        probes.push_back({(a.x + b.x) / 2, (a.y + b.y) / 2, 0});
      }
    auto inOldStar = [&](const Point3& p) {  // rounding can put a midpoint just outside
      for (std::size_t i = 0; i < d; ++i) {
        const K::Point_2 c = xy(star.centre), a = xy(star.ring[i]), b = xy(star.ring[(i + 1) % d]);
        if (CGAL::orientation(c, a, xy(p)) != CGAL::RIGHT_TURN && CGAL::orientation(a, b, xy(p)) != CGAL::RIGHT_TURN &&
            CGAL::orientation(b, c, xy(p)) != CGAL::RIGHT_TURN)
          return true;
      }
      return false;
    };
    auto holds = [&](std::size_t j, const Point3& p) {
      const K::Point_2 a = xy(star.ring[fill[j][0]]), b = xy(star.ring[fill[j][1]]), c = xy(star.ring[fill[j][2]]);
      return CGAL::orientation(a, b, xy(p)) != CGAL::RIGHT_TURN && CGAL::orientation(b, c, xy(p)) != CGAL::RIGHT_TURN &&
             CGAL::orientation(c, a, xy(p)) != CGAL::RIGHT_TURN;
    };
    for (const Point3& p : probes) {
      if (!inOldStar(p)) continue;
      int first = -1;
      for (std::size_t j = 0; j < fill.size() && first < 0; ++j)
        if (holds(j, p)) first = static_cast<int>(j);
      ASSERT_GE(first, 0);
      for (int likely = -1; likely < static_cast<int>(fill.size()); ++likely) {
        const int expected = likely >= 0 && holds(likely, p) ? likely : first;
        ASSERT_EQ(triangleHolding(star, fill.data(), fill.size(), p, convexRing(star), likely), expected)
            << "star of degree " << d << ", likely " << likely;
        ASSERT_EQ(triangleHolding(star, fill.data(), fill.size(), p, false, likely), expected)
            << "star of degree " << d << ", likely " << likely;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 5000);
}

}  // namespace
}  // namespace tinlod
