// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "mesh_checks.h"
#include "tinlod/error.h"
#include "tinlod/triangulation.h"

namespace tinlod {
namespace {

const Feedback kQuiet;
const ProgressRange kRange(kQuiet, 0, 1);

TinVertex at(double x, double y, double z = 0) {
  TinVertex v;
  v.x = x, v.y = y, v.z = z;
  return v;
}

TEST(Triangulation, SquareWithCentreGivesFourCounterClockwiseTriangles) {
  Tin tin;
  tin.vertices = {at(0, 0), at(10, 0), at(10, 10), at(0, 10), at(5, 5.1)};
  tin.triangles = delaunayTriangles(tin.vertices, kRange).triangles;
  EXPECT_EQ(tin.triangles.size(), 4u);
  EXPECT_EQ(test::clockwiseTriangles(tin), 0u);
  EXPECT_DOUBLE_EQ(totalArea(tin), 100.0);
}

TEST(Triangulation, RandomPointsAreDelaunayWithEulerOfADisk) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 1000);
  Tin tin;
  for (int i = 0; i < 5000; ++i) tin.vertices.push_back(at(u(rng), u(rng), u(rng)));
  tin.triangles = delaunayTriangles(tin.vertices, kRange).triangles;
  EXPECT_EQ(test::delaunayViolations(tin), 0u);
  EXPECT_EQ(test::clockwiseTriangles(tin), 0u);
  const test::Topology t = test::analyseTopology(tin);
  EXPECT_EQ(t.problem, "");
  EXPECT_EQ(t.components, 1u);
  EXPECT_EQ(t.boundaryLoops, 1u);
  EXPECT_EQ(t.eulerCharacteristic(), 1);
}

TEST(Triangulation, DuplicatePointIsLeftOut) {
  Tin tin;
  tin.vertices = {at(0, 0), at(1, 0), at(0, 1), at(1, 0)};
  tin.triangles = delaunayTriangles(tin.vertices, kRange).triangles;
  ASSERT_EQ(tin.triangles.size(), 1u);
  for (VertexId v : tin.triangles[0]) EXPECT_NE(v, 3u);
}

TEST(Triangulation, NeighboursAreAcrossTheOppositeEdge) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 100);
  std::vector<TinVertex> vertices;
  for (int i = 0; i < 300; ++i) vertices.push_back(at(u(rng), u(rng)));
  const Triangulation tr = delaunayTriangles(vertices, kRange);
  std::size_t hull = 0;
  for (std::size_t t = 0; t < tr.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t n = tr.neighbours[t][k];
      if (n == kNoNeighbour) {
        ++hull;
        continue;
      }
      // The neighbour holds both vertices of the edge opposite corner k, and not corner k.
      const Triangle& a = tr.triangles[t];
      const Triangle& b = tr.triangles[n];
      auto has = [&](VertexId v) { return std::find(b.begin(), b.end(), v) != b.end(); };
      EXPECT_TRUE(has(a[(k + 1) % 3]) && has(a[(k + 2) % 3]) && !has(a[k]));
    }
  Tin tin;
  tin.vertices = vertices;
  tin.triangles = tr.triangles;
  EXPECT_EQ(hull, test::analyseTopology(tin).edges * 2 - 3 * tr.triangles.size());
}

TEST(Triangulation, CancelStopsWithCancelled) {
  Tin tin;
  for (int i = 0; i < 200000; ++i) tin.vertices.push_back(at(i % 500 + 0.001 * i, i / 500));
  Feedback cancelling;
  cancelling.progress = [](double f, const std::string&) { return f < 0.3; };
  EXPECT_THROW(delaunayTriangles(tin.vertices, ProgressRange(cancelling, 0, 1)), Cancelled);
}

}  // namespace
}  // namespace tinlod
