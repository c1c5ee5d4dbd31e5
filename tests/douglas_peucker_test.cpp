// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "tinlod/douglas_peucker.h"

namespace tinlod {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The classic recursion, written apart from the code under test: keep the farthest vertex
// of a stretch when it is more than the tolerance from the segment, and recurse.
double distanceToSegment(const LinePoint& p, const LinePoint& a, const LinePoint& b) {
  const double dx = b[0] - a[0], dy = b[1] - a[1], len2 = dx * dx + dy * dy;
  const double t = len2 == 0 ? 0 : std::max(0.0, std::min(1.0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2));
  return std::hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
}
void classic(const Polyline& line, std::size_t a, std::size_t b, double tolerance, std::vector<bool>& keep) {
  std::size_t far = a;
  double best = -1;
  for (std::size_t i = a + 1; i < b; ++i) {
    const double d = distanceToSegment(line[i], line[a], line[b]);
    if (d > best) best = d, far = i;
  }
  if (far == a || best <= tolerance) return;
  keep[far] = true;
  classic(line, a, far, tolerance, keep);
  classic(line, far, b, tolerance, keep);
}
Polyline classicDouglasPeucker(const Polyline& line, double tolerance) {
  std::vector<bool> keep(line.size(), false);
  keep.front() = keep.back() = true;
  classic(line, 0, line.size() - 1, tolerance, keep);
  Polyline out;
  for (std::size_t i = 0; i < line.size(); ++i)
    if (keep[i]) out.push_back(line[i]);
  return out;
}

TEST(DouglasPeucker, HandWorkedValues) {
  const Polyline line{{0, 0}, {1, 1}, {2, 0}, {3, 3}, {4, 0}};
  const std::vector<double> v = douglasPeuckerValues(line);
  ASSERT_EQ(v.size(), 5u);
  EXPECT_EQ(v[0], kInfinity);
  EXPECT_EQ(v[4], kInfinity);
  EXPECT_DOUBLE_EQ(v[3], 3);             // farthest from (0,0)-(4,0)
  EXPECT_DOUBLE_EQ(v[2], std::sqrt(2));  // farthest from (0,0)-(3,3)
  EXPECT_DOUBLE_EQ(v[1], 1);             // farthest from (0,0)-(2,0)
  EXPECT_EQ(simplified(line, v, 1.2), (Polyline{{0, 0}, {2, 0}, {3, 3}, {4, 0}}));
  EXPECT_EQ(simplified(line, v, 2), (Polyline{{0, 0}, {3, 3}, {4, 0}}));
  EXPECT_EQ(simplified(line, v, 5), (Polyline{{0, 0}, {4, 0}}));
}

TEST(DouglasPeucker, ValueIsCappedByTheVerticesAbove) {
  // The middle vertex is far from the chord but hangs off a vertex of value 1: it cannot
  // outlive it.
  const Polyline line{{0, 0}, {5, 1}, {6, 0.5}, {6.5, 10}, {7, 0.5}, {10, 0}};
  const std::vector<double> v = douglasPeuckerValues(line);
  for (std::size_t i = 1; i + 1 < line.size(); ++i) EXPECT_LT(v[i], kInfinity);
  EXPECT_LE(v[1], v[3]);
}

TEST(DouglasPeucker, EveryThresholdReproducesTheClassicSimplification) {
  std::mt19937 rng(5);
  std::normal_distribution<double> step(0, 1);
  for (int trial = 0; trial < 20; ++trial) {
    Polyline line{{0, 0}};
    for (int i = 0; i < 400; ++i) line.push_back({line.back()[0] + 1 + std::fabs(step(rng)), line.back()[1] + 3 * step(rng)});
    const std::vector<double> v = douglasPeuckerValues(line);
    for (double t : {0.0, 0.5, 1.0, 2.0, 5.0, 10.0, 30.0}) EXPECT_EQ(simplified(line, v, t), classicDouglasPeucker(line, t)) << t;
  }
}

TEST(DouglasPeucker, ClosedContourAndShortLines) {
  const Polyline ring{{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}};
  const std::vector<double> v = douglasPeuckerValues(ring);
  EXPECT_EQ(v.front(), kInfinity);
  EXPECT_EQ(v.back(), kInfinity);
  EXPECT_EQ(v[2], kInfinity);  // the corner farthest from the start anchors the ring
  EXPECT_EQ(simplified(ring, v, 1e9), (Polyline{{0, 0}, {1, 1}, {0, 0}}));  // never a point
  EXPECT_EQ(douglasPeuckerValues(Polyline{{0, 0}, {1, 1}}), (std::vector<double>{kInfinity, kInfinity}));
  EXPECT_TRUE(douglasPeuckerValues(Polyline{}).empty());
}

TEST(DouglasPeucker, CrossingsOfSimplifiedContours) {
  EXPECT_EQ(crossingCount({{{0, 0}, {2, 2}}, {{0, 2}, {2, 0}}}), 1u);
  EXPECT_EQ(crossingCount({{{0, 0}, {2, 0}}, {{0, 1}, {2, 1}}}), 0u);
  // A thin extent (all on one vertical line): overlapping segments touch; the grid copes.
  EXPECT_EQ(crossingCount({{{0, 0}, {0, 10}}, {{0, 5}, {0, 20}}, {{0, 30}, {0, 40}}}), 1u);
  EXPECT_EQ(crossingCount({{{0, 0}, {1, 1}}}), 0u);
  // Two nested peaks, one metre apart everywhere; the upper one simplified to its chord
  // cuts through the lower peak twice.
  const Polyline lower{{0, 0}, {5, 4}, {10, 0}};
  const Polyline upper{{0, 1}, {5, 5}, {10, 1}};
  EXPECT_EQ(crossingCount({lower, upper}), 0u);
  const Polyline a = simplified(lower, douglasPeuckerValues(lower), 0.5);
  const Polyline b = simplified(upper, douglasPeuckerValues(upper), 5);
  EXPECT_EQ(a, lower);
  EXPECT_EQ(b, (Polyline{{0, 1}, {10, 1}}));
  EXPECT_EQ(crossingCount({a, b}), 2u);
}

}  // namespace
}  // namespace tinlod
