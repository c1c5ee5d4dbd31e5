// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <set>
#include <tuple>
#include <vector>

#include "test_support.h"
#include "tinlod/sample_job.h"
#include "tinlod/tin.h"

namespace tinlod {
namespace {

// A 64 x 64 grid numbered row by row, as the sampler numbers its points, with each
// square cut into two counter-clockwise triangles.
Tin rowByRowGrid() {
  constexpr int n = 64;
  Tin tin;
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) tin.vertices.push_back({c * 10.0, r * 10.0, double(r * c)});
  auto id = [](int r, int c) { return VertexId(r * n + c); };
  for (int r = 0; r + 1 < n; ++r)
    for (int c = 0; c + 1 < n; ++c) {
      tin.triangles.push_back({id(r, c), id(r, c + 1), id(r + 1, c + 1)});
      tin.triangles.push_back({id(r, c), id(r + 1, c + 1), id(r + 1, c)});
    }
  return tin;
}

// Each triangle's neighbour across the edge opposite each corner, by brute force.
std::vector<std::array<std::int32_t, 3>> neighboursOf(const Tin& tin) {
  std::map<std::pair<VertexId, VertexId>, std::int32_t> byEdge;
  for (std::size_t t = 0; t < tin.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) byEdge[{tin.triangles[t][k], tin.triangles[t][(k + 1) % 3]}] = std::int32_t(t);
  std::vector<std::array<std::int32_t, 3>> out(tin.triangles.size());
  for (std::size_t t = 0; t < tin.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const auto it = byEdge.find({tin.triangles[t][(k + 2) % 3], tin.triangles[t][(k + 1) % 3]});
      out[t][k] = it == byEdge.end() ? -1 : it->second;
    }
  return out;
}

using Corner = std::tuple<double, double, double>;

std::multiset<std::vector<Corner>> geometry(const Tin& tin) {
  std::multiset<std::vector<Corner>> out;
  for (const Triangle& t : tin.triangles) {
    std::vector<Corner> corners;
    for (VertexId v : t) corners.emplace_back(tin.vertices[v].x, tin.vertices[v].y, tin.vertices[v].z);
    std::rotate(corners.begin(), std::min_element(corners.begin(), corners.end()), corners.end());  // same cycle
    out.insert(corners);
  }
  return out;
}

// Half the edges of a row-by-row grid join vertices a row (64 ids) apart; along the
// curve, most neighbours are a few ids apart.
double medianIdGap(const Tin& tin) {
  std::vector<long> gaps;
  for (const Triangle& t : tin.triangles)
    for (int k = 0; k < 3; ++k) gaps.push_back(std::labs(long(t[k]) - long(t[(k + 1) % 3])));
  std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
  return double(gaps[gaps.size() / 2]);
}

TEST(Tin, OrderSpatiallyKeepsTheTrianglesAndBringsNeighboursTogether) {
  Tin tin = rowByRowGrid();
  tin.neighbours = neighboursOf(tin);
  const auto before = geometry(tin);
  const double area = totalArea(tin);
  EXPECT_GE(medianIdGap(tin), 63);
  orderSpatially(tin);
  EXPECT_EQ(geometry(tin), before);  // same triangles, same corners, still counter-clockwise
  EXPECT_DOUBLE_EQ(totalArea(tin), area);
  EXPECT_LE(medianIdGap(tin), 8);
  EXPECT_EQ(tin.neighbours, neighboursOf(tin));  // the neighbours follow their triangles
  for (std::size_t i = 1; i < tin.triangles.size(); ++i) {
    const Triangle &a = tin.triangles[i - 1], &b = tin.triangles[i];
    ASSERT_LE(*std::min_element(a.begin(), a.end()), *std::min_element(b.begin(), b.end())) << "triangle " << i;
  }
}

// The sampler keeps its triangulation's neighbours through the nodata cut (a dropped
// neighbour leaves an outline edge) and the spatial order.
TEST(Tin, SampledTinKeepsItsTriangulationsNeighbours) {
  const Tin tin = sampleTin(test::smallSyntheticDem(), {}, ProgressRange(Feedback{}, 0, 1));
  const auto brute = neighboursOf(tin);
  EXPECT_EQ(tin.neighbours, brute);
  std::size_t outline = 0;
  for (const auto& n : brute) outline += std::count(n.begin(), n.end(), -1);
  EXPECT_GT(outline, 100u);  // the void's edge and the raster's
}

TEST(Tin, OrderSpatiallyOfOnePointAndOfNothing) {
  Tin one;
  one.vertices.push_back({5, 5, 1});
  orderSpatially(one);
  EXPECT_EQ(one.vertices.size(), 1u);
  Tin none;
  EXPECT_NO_THROW(orderSpatially(none));
}

}  // namespace
}  // namespace tinlod
