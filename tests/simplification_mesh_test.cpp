// SPDX-License-Identifier: GPL-3.0-or-later
// The simplifier's own triangle arrays: deleting stars in rounds keeps every link.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "simplification_mesh.h"
#include "tinlod/feedback.h"
#include "tinlod/triangulation.h"

namespace tinlod {
namespace {

const ProgressRange kQuiet(Feedback{}, 0, 1);

// A centre with `n` neighbours on a circle, inside a ring of 2n points twice as far, and
// random points beyond: the centre's star has degree n.
Tin wheel(int n, unsigned seed) {
  Tin tin;
  tin.vertices.push_back({0, 0, 10});
  for (int i = 0; i < n; ++i) tin.vertices.push_back({1000 * std::cos(2 * M_PI * i / n), 1000 * std::sin(2 * M_PI * i / n), 1});
  for (int i = 0; i < 2 * n; ++i)
    tin.vertices.push_back({2000 * std::cos(M_PI * (i + 0.5) / n), 2000 * std::sin(M_PI * (i + 0.5) / n), 2});
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-4000, 4000);
  for (int i = 0; i < 300; ++i) {
    const double x = u(rng), y = u(rng);
    if (std::hypot(x, y) > 2300) tin.vertices.push_back({x, y, 3});
  }
  tin.triangles = delaunayTriangles(tin.vertices, kQuiet).triangles;
  return tin;
}

// Deletes an independent set in one round, as the simplifier does.
void deleteRound(SimplificationMesh& mesh, const std::vector<VertexId>& picks, std::int32_t& nextId) {
  std::vector<std::vector<VertexId>> rings(picks.size());
  std::vector<std::vector<std::int32_t>> slots(picks.size()), outer(picks.size());
  std::vector<std::vector<LocalTriangle>> fills(picks.size());
  mesh.beginRound();
  for (std::size_t i = 0; i < picks.size(); ++i) {
    const int d = mesh.degree(picks[i]);
    rings[i].resize(d), slots[i].resize(d), outer[i].resize(d);
    Star star;
    mesh.starOf(picks[i], rings[i].data(), slots[i].data(), outer[i].data(), star);
    retriangulateStar(star, fills[i]);
    std::vector<int> onEdge(d);
    ringEdgeTriangles(fills[i].data(), d, onEdge.data());
    mesh.retire({rings[i].data(), slots[i].data(), outer[i].data(), d}, onEdge.data());
  }
  for (std::size_t i = 0; i < picks.size(); ++i) {
    std::vector<std::int32_t> ids;
    for (std::size_t j = 0; j < fills[i].size(); ++j) ids.push_back(nextId++);
    mesh.replaceStar({rings[i].data(), slots[i].data(), outer[i].data(), static_cast<int>(rings[i].size())},
                     fills[i].data(), ids.data());
  }
  mesh.planCompaction();
  mesh.applyCompaction();
}

// Level 0 is linked from the triangulation's neighbours when they fit the triangles, and
// by the edge search when they are missing or no longer fit; the links are the same.
TEST(SimplificationMesh, LinksFromTheTriangulationsNeighboursWhenTheyFit) {
  Tin tin = wheel(7, 5);
  const Triangulation dt = delaunayTriangles(tin.vertices, kQuiet);
  tin.neighbours = dt.neighbours;
  const SimplificationMesh given(tin);
  EXPECT_TRUE(given.linkedFromNeighbours());
  EXPECT_EQ(given.brokenLinks(), 0u);
  Tin rotated = tin;  // each triangle starts at another corner: the neighbours no longer fit
  for (Triangle& t : rotated.triangles) std::rotate(t.begin(), t.begin() + 1, t.end());
  const SimplificationMesh searched(rotated);
  EXPECT_FALSE(searched.linkedFromNeighbours());
  EXPECT_EQ(searched.brokenLinks(), 0u);
  tin.neighbours.clear();
  EXPECT_FALSE(SimplificationMesh(tin).linkedFromNeighbours());
  std::size_t closed = 0;
  for (VertexId v = 0; v < tin.vertices.size(); ++v) {  // the same outline and the same stars
    ASSERT_EQ(given.open(v), searched.open(v)) << v;
    if (given.open(v)) continue;
    EXPECT_EQ(given.degree(v), searched.degree(v)) << v;
    ++closed;
  }
  EXPECT_GT(closed, 10u);
}

TEST(SimplificationMesh, DeletingAHugeStarKeepsEveryLink) {
  const Tin tin = wheel(100, 3);
  SimplificationMesh mesh(tin);
  ASSERT_EQ(mesh.brokenLinks(), 0u);
  ASSERT_EQ(mesh.degree(0), 100);
  auto ringDegrees = [&] {
    int sum = 0;
    for (VertexId v = 1; v <= 100; ++v) sum += mesh.degree(v);
    return sum;
  };
  const int before = ringDegrees();
  std::int32_t nextId = static_cast<std::int32_t>(tin.triangles.size());
  deleteRound(mesh, {0}, nextId);
  EXPECT_EQ(mesh.liveTriangles(), tin.triangles.size() - 2);
  ASSERT_EQ(mesh.brokenLinks(), 0u);  // before walking: a broken link could send a walk round forever
  // Walking the ring's stars now crosses the new triangles: each ring vertex lost the
  // centre and gained its share of the 97 diagonals.
  EXPECT_EQ(ringDegrees(), before - 100 + 2 * 97);
}

// Neighbouring stars in the same round (sharing ring vertices and ring edges) link to
// each other's new triangles.
TEST(SimplificationMesh, StarsDeletedTogetherLinkToEachOther) {
  const Tin tin = wheel(12, 5);
  SimplificationMesh mesh(tin);
  // Every other vertex of the inner ring: independent, each star touching the next.
  std::vector<VertexId> picks;
  for (VertexId v = 1; v <= 12; v += 2) picks.push_back(v);
  std::int32_t nextId = static_cast<std::int32_t>(tin.triangles.size());
  deleteRound(mesh, picks, nextId);
  EXPECT_EQ(mesh.liveTriangles(), tin.triangles.size() - 2 * picks.size());
  ASSERT_EQ(mesh.brokenLinks(), 0u);
  EXPECT_EQ(mesh.degree(0), 6);
}

}  // namespace
}  // namespace tinlod
