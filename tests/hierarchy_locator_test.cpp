// SPDX-License-Identifier: GPL-3.0-or-later
// Point location through the hierarchy against a brute-force search of each level.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "test_support.h"
#include "tinlod/crs_transform.h"
#include "tinlod/dem_reader.h"
#include "tinlod/error.h"
#include "tinlod/hierarchy_builder.h"
#include "tinlod/hierarchy_locator.h"
#include "tinlod/sample_job.h"

namespace tinlod {
namespace {

const ProgressRange kQuiet(Feedback{}, 0, 1);
// Barycentric slack of the brute force: a random point is never this close to an edge,
// so only points on a shared edge (or a vertex) find more than one triangle.
constexpr double kSlack = 1e-12;
constexpr double kHeightTolerance = 1e-9;

Hierarchy buildFrom(const Dem& dem, const SampleOptions& so = {}) {
  const Tin tin = sampleTin(dem, so, kQuiet);
  Hierarchy h = buildHierarchy(tin, dem, {}, HierarchyOptions{}, kQuiet);
  linkGroups(h);
  return h;
}

// One level's triangles, flattened for the brute force: corners, heights and box.
struct FlatTriangle {
  std::uint32_t id;
  double x[3], y[3], z[3];
  double x0, y0, x1, y1;
};

std::vector<FlatTriangle> flatten(const Hierarchy& h, std::int32_t level) {
  std::vector<FlatTriangle> out;
  for (std::uint32_t t : h.levelTriangles(level)) {
    FlatTriangle f{t, {}, {}, {}, 0, 0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      const TinVertex& v = h.base.vertices[h.triangles[t].v[k]];
      f.x[k] = v.x, f.y[k] = v.y, f.z[k] = v.z;
    }
    f.x0 = std::min({f.x[0], f.x[1], f.x[2]}), f.x1 = std::max({f.x[0], f.x[1], f.x[2]});
    f.y0 = std::min({f.y[0], f.y[1], f.y[2]}), f.y1 = std::max({f.y[0], f.y[1], f.y[2]});
    out.push_back(f);
  }
  return out;
}

// Every triangle of the level that holds (x, y), edges included, and the height there.
struct Containing {
  std::vector<std::uint32_t> triangles;
  double z = NAN;
};

Containing bruteForce(const std::vector<FlatTriangle>& level, double x, double y) {
  Containing out;
  for (const FlatTriangle& f : level) {
    if (x < f.x0 || x > f.x1 || y < f.y0 || y > f.y1) continue;
    double w[3], area = 0;
    for (int k = 0; k < 3; ++k) {
      const int b = (k + 1) % 3, c = (k + 2) % 3;
      w[k] = (f.x[b] - x) * (f.y[c] - y) - (f.y[b] - y) * (f.x[c] - x);
      area += w[k];
    }
    if (std::min({w[0], w[1], w[2]}) < -kSlack * area) continue;
    out.triangles.push_back(f.id);
    if (std::isnan(out.z)) out.z = (w[0] * f.z[0] + w[1] * f.z[1] + w[2] * f.z[2]) / area;
  }
  return out;
}

struct Box {
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
};

Box boxOf(const Tin& tin) {
  Box b;
  for (const TinVertex& v : tin.vertices)
    b.x0 = std::min(b.x0, v.x), b.y0 = std::min(b.y0, v.y), b.x1 = std::max(b.x1, v.x), b.y1 = std::max(b.y1, v.y);
  return b;
}

// Uniform points over the TIN's box widened by a tenth on every side: some fall
// outside, some in holes.
std::vector<std::array<double, 2>> randomPoints(const Tin& tin, std::size_t count, unsigned seed) {
  const Box b = boxOf(tin);
  const double mx = 0.1 * (b.x1 - b.x0), my = 0.1 * (b.y1 - b.y0);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(b.x0 - mx, b.x1 + mx), uy(b.y0 - my, b.y1 + my);
  std::vector<std::array<double, 2>> points(count);
  for (auto& p : points) p = {ux(rng), uy(rng)};
  return points;
}

struct Agreement {
  std::size_t found = 0, missed = 0;
  std::size_t reached = 0;  // of the missed, those within reach of a triangle
};

// The distance from (x, y) to the triangle, 0 inside it.
double distanceTo(const FlatTriangle& f, double x, double y) {
  double inside = 1, nearest = INFINITY;
  const double area = (f.x[1] - f.x[0]) * (f.y[2] - f.y[0]) - (f.y[1] - f.y[0]) * (f.x[2] - f.x[0]);
  for (int k = 0; k < 3; ++k) {
    const double ax = f.x[k], ay = f.y[k], bx = f.x[(k + 1) % 3], by = f.y[(k + 1) % 3];
    if (((bx - ax) * (y - ay) - (by - ay) * (x - ax)) * area < 0) inside = 0;
    const double len2 = (bx - ax) * (bx - ax) + (by - ay) * (by - ay);
    const double t = std::clamp(((x - ax) * (bx - ax) + (y - ay) * (by - ay)) / len2, 0.0, 1.0);
    nearest = std::min(nearest, std::hypot(x - ax - t * (bx - ax), y - ay - t * (by - ay)));
  }
  return inside ? 0 : nearest;
}

// The locator's answer at `level` is one of the brute force's triangles, with the same
// height; for a point in none, nothing, or a triangle within the locator's reach and the
// height of its plane.
Agreement expectAgreement(const Hierarchy& h, const HierarchyLocator& locator, std::int32_t level,
                          const std::vector<std::array<double, 2>>& points) {
  SCOPED_TRACE("level " + std::to_string(level));
  const std::vector<FlatTriangle> flat = flatten(h, level);
  Agreement a;
  for (const auto& [x, y] : points) {
    const Containing expected = bruteForce(flat, x, y);
    const LocatedPoint got = locator.locate(x, y, level);
    if (expected.triangles.empty()) {
      ++a.missed;
      if (!got.found()) {
        EXPECT_TRUE(std::isnan(got.z));
        continue;
      }
      ++a.reached;
      const auto f = std::find_if(flat.begin(), flat.end(), [&](const FlatTriangle& t) { return t.id == got.triangle; });
      if (f == flat.end()) {
        ADD_FAILURE() << got.triangle << " is not a triangle of the level";
        continue;
      }
      EXPECT_LE(distanceTo(*f, x, y), locator.reach() * (1 + 1e-9)) << "(" << x << ", " << y << ") found in " << got.triangle;
      double w[3], area = 0;
      for (int k = 0; k < 3; ++k) {
        const int b = (k + 1) % 3, c = (k + 2) % 3;
        w[k] = (f->x[b] - x) * (f->y[c] - y) - (f->y[b] - y) * (f->x[c] - x);
        area += w[k];
      }
      EXPECT_NEAR(got.z, (w[0] * f->z[0] + w[1] * f->z[1] + w[2] * f->z[2]) / area, kHeightTolerance);
      continue;
    }
    ++a.found;
    if (!got.found()) {
      ADD_FAILURE() << "(" << x << ", " << y << ") is in triangle " << expected.triangles.front()
                    << " but was not found";
      continue;
    }
    EXPECT_NE(std::find(expected.triangles.begin(), expected.triangles.end(), got.triangle), expected.triangles.end())
        << "(" << x << ", " << y << ") found in triangle " << got.triangle << ", which does not hold it";
    EXPECT_NEAR(got.z, expected.z, kHeightTolerance) << "(" << x << ", " << y << ")";
  }
  return a;
}

TEST(HierarchyLocator, AgreesWithBruteForceAtEveryLevel) {
  const Hierarchy h = buildFrom(test::smallSyntheticDem());
  ASSERT_GE(h.coarsest(), 3);
  const HierarchyLocator locator(h);
  const auto points = randomPoints(h.base, 3000, 12345);
  for (std::int32_t level = 0; level <= h.coarsest(); ++level) {
    const Agreement a = expectAgreement(h, locator, level, points);
    // The widened box (69 % of it is the raster's) and the void give misses.
    EXPECT_GT(a.found, points.size() / 2);
    EXPECT_GT(a.missed, points.size() / 5);
  }
}

// A DEM in degrees: its edge rows and columns are curves in the TIN's UTM zone, and their
// cells' centres lie a fraction of a millimetre outside the straight edges between the
// vertices (a user trial found 463 of zion_srtm3's 465 bottom-row centres off the TIN).
// Every one is located, at every level, with the DEM's height; half a cell beyond, none.
TEST(HierarchyLocator, EdgeCellCentresOfADemInDegreesAreOnTheTin) {
  const Dem dem = test::makeGeographicDem(150, 120, -113.2, 37.4);
  const Hierarchy h = buildFrom(dem);
  ASSERT_GE(h.coarsest(), 3);
  const HierarchyLocator locator(h);
  EXPECT_GT(locator.reach(), 0.05 * 60);  // 5 % of a cell of 1/1200 degree, 66 to 93 m here
  EXPECT_LT(locator.reach(), 0.05 * 100);
  std::vector<double> x, y, z, outX, outY;
  const auto centre = [&](double col, double row, std::vector<double>& xs, std::vector<double>& ys) {
    xs.push_back(dem.geotransform[0] + (col + 0.5) * dem.geotransform[1]);
    ys.push_back(dem.geotransform[3] + (row + 0.5) * dem.geotransform[5]);
  };
  for (int c = 0; c < dem.width; ++c)
    for (int r : {0, dem.height - 1}) {
      centre(c, r, x, y), z.push_back(dem.at(r, c));
      centre(c, r == 0 ? -0.5 : r + 0.5, outX, outY);
    }
  for (int r = 0; r < dem.height; ++r)
    for (int c : {0, dem.width - 1}) {
      centre(c, r, x, y), z.push_back(dem.at(r, c));
      centre(c == 0 ? -0.5 : c + 0.5, r, outX, outY);
    }
  const CrsTransform toTin = CrsTransform::forDem(dem, "", "", kQuiet);
  toTin.apply(x, y);
  toTin.apply(outX, outY);
  for (std::int32_t level = 0; level <= h.coarsest(); ++level) {
    std::size_t missed = 0, beyond = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const LocatedPoint p = locator.locate(x[i], y[i], level);
      missed += !p.found();
      // Within what the jitter (under 1 m along the edge) makes of slopes of 2 m a cell.
      if (p.found()) EXPECT_NEAR(p.z, z[i], 0.05) << "level " << level;
    }
    for (std::size_t i = 0; i < outX.size(); ++i) beyond += locator.locate(outX[i], outY[i], level).found();
    EXPECT_EQ(missed, 0u) << "level " << level;
    EXPECT_EQ(beyond, 0u) << "level " << level;
  }
}

// The reach is the raster edge's alone: just outside a hole's outline (1 % of a cell, within
// the reach) a point stays off the TIN, where nodata cells are (a user trial found a nodata
// cell's centre given a height 3 m off a coarse level's outline).
TEST(HierarchyLocator, PointsJustOutsideAHoleAreNotFound) {
  const Dem dem = test::smallSyntheticDem();
  const Hierarchy h = buildFrom(dem);
  const HierarchyLocator locator(h);
  const double cell = dem.geotransform[1];
  ASSERT_GT(locator.reach(), 0.01 * cell);
  for (std::int32_t level : {0, h.coarsest()}) {
    const std::vector<FlatTriangle> flat = flatten(h, level);
    std::map<std::pair<VertexId, VertexId>, int> edges;  // directed edge -> its triangle's count
    for (std::uint32_t t : h.levelTriangles(level))
      for (int k = 0; k < 3; ++k) ++edges[{h.triangles[t].v[k], h.triangles[t].v[(k + 1) % 3]}];
    std::size_t tested = 0;
    for (const auto& [e, n] : edges) {
      if (edges.count({e.second, e.first})) continue;  // inside: a triangle on both sides
      const TinVertex &a = h.base.vertices[e.first], &b = h.base.vertices[e.second];
      if ((a.row == b.row && (a.row == 0 || a.row == dem.height - 1)) || (a.col == b.col && (a.col == 0 || a.col == dem.width - 1)))
        continue;  // the raster's edge
      const double len = std::hypot(b.x - a.x, b.y - a.y);
      // Outside a counter-clockwise triangle's edge is to its right.
      const double x = 0.5 * (a.x + b.x) + 0.01 * cell * (b.y - a.y) / len, y = 0.5 * (a.y + b.y) - 0.01 * cell * (b.x - a.x) / len;
      if (!bruteForce(flat, x, y).triangles.empty()) continue;
      EXPECT_FALSE(locator.locate(x, y, level).found()) << "level " << level << " (" << x << ", " << y << ")";
      ++tested;
    }
    EXPECT_GT(tested, 20u) << "level " << level;
  }
}

// A long edge of a DEM in degrees, far from the UTM zone's meridian and far north, is a
// curve in the TIN's CRS, and its coarse levels have slivers along it centimetres thin:
// every edge centre is still found at every level (it failed with nudges from a 64th of
// the reach, and with the reach from the cells' width alone, 2 m, not their 3 m size).
TEST(HierarchyLocator, ALongCurvedRasterEdgeKeepsItsCentresWithinReach) {
  const Dem dem = test::makeGeographicDem(1500, 30, 14.4, 64.0);  // 1.25 degrees wide at 64 N
  const Hierarchy h = buildFrom(dem);
  ASSERT_GE(h.coarsest(), 8);
  const HierarchyLocator locator(h);
  std::vector<double> x, y;
  for (int c = 0; c < dem.width; ++c)
    for (int r : {0, dem.height - 1}) {
      x.push_back(dem.geotransform[0] + (c + 0.5) * dem.geotransform[1]);
      y.push_back(dem.geotransform[3] + (r + 0.5) * dem.geotransform[5]);
    }
  CrsTransform::forDem(dem, "", "", kQuiet).apply(x, y);
  for (std::int32_t level = 0; level <= h.coarsest(); ++level) {
    std::size_t missed = 0;
    const std::vector<FlatTriangle> flat = flatten(h, level);
    double worst = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (locator.locate(x[i], y[i], level).found()) continue;
      ++missed;
      double nearest = INFINITY;
      for (const FlatTriangle& f : flat) nearest = std::min(nearest, distanceTo(f, x[i], y[i]));
      worst = std::max(worst, nearest);
    }
    EXPECT_EQ(missed, 0u) << "level " << level << " of " << h.coarsest() << ": the furthest off the TIN by " << worst
                          << " m, the reach " << locator.reach() << " m";
  }
}

TEST(HierarchyLocator, PointsInTheVoidAndOutsideAreNotFound) {
  const Dem dem = test::smallSyntheticDem();
  const Hierarchy h = buildFrom(dem);
  const HierarchyLocator locator(h);
  // The void's centre (synthetic_dem.cpp: 72 % across, 60 % up), in the DEM's UTM CRS,
  // which sampling keeps; a point beside it is on data.
  const double w = dem.width * dem.geotransform[1], ht = dem.height * -dem.geotransform[5];
  const double voidX = dem.geotransform[0] + 0.72 * w, voidY = dem.geotransform[3] - ht + 0.6 * ht;
  for (std::int32_t level = 0; level <= h.coarsest(); ++level) {
    EXPECT_FALSE(locator.locate(voidX, voidY, level).found()) << "level " << level;
    EXPECT_TRUE(locator.locate(voidX, voidY - 0.2 * ht, level).found()) << "level " << level;
    EXPECT_FALSE(locator.locate(dem.geotransform[0] - 100, voidY, level).found());
    EXPECT_FALSE(locator.locate(voidX, dem.geotransform[3] + 1e6, level).found());
    EXPECT_FALSE(locator.locate(NAN, voidY, level).found());
    EXPECT_FALSE(locator.locate(voidX, INFINITY, level).found());
  }
}

// Vertices are on the edges of several triangles at once: the closed test finds them,
// including the vertices on the outline and around the void, with their own height.
TEST(HierarchyLocator, VerticesAreFoundWithTheirOwnHeightAtEveryLevel) {
  const Hierarchy h = buildFrom(test::smallSyntheticDem());
  const HierarchyLocator locator(h);
  for (std::int32_t level = 0; level <= h.coarsest(); ++level) {
    std::size_t tested = 0;
    for (std::size_t v = 0; v < h.base.vertices.size(); ++v) {
      if (h.vertexLevel[v] < level) continue;
      const TinVertex& p = h.base.vertices[v];
      const LocatedPoint got = locator.locate(p.x, p.y, level);
      ASSERT_TRUE(got.found()) << "vertex " << v << " at level " << level;
      const HierarchyTriangle& t = h.triangles[got.triangle];
      EXPECT_TRUE(t.firstLevel <= level && level <= t.lastLevel)
          << "triangle " << got.triangle << " is not of level " << level;
      EXPECT_NE(std::find(t.v.begin(), t.v.end(), VertexId(v)), t.v.end()) << "vertex " << v << " at level " << level;
      EXPECT_EQ(got.z, p.z) << "vertex " << v << " at level " << level;
      ++tested;
    }
    EXPECT_EQ(tested, h.levels[level].vertices);
  }
}

TEST(HierarchyLocator, SamePointSameAnswer) {
  const Hierarchy h = buildFrom(test::smallSyntheticDem());
  const HierarchyLocator a(h), b(h);
  // b answers the points in the other order: no answer depends on the queries before it.
  const auto points = randomPoints(h.base, 500, 7);
  std::vector<LocatedPoint> backwards(points.size());
  for (std::size_t i = points.size(); i-- > 0;) backwards[i] = b.locate(points[i][0], points[i][1]);
  std::size_t found = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const LocatedPoint p = a.locate(points[i][0], points[i][1]), &q = backwards[i];
    EXPECT_EQ(p.triangle, q.triangle);
    if (p.found()) {
      EXPECT_EQ(p.z, q.z);
      ++found;
    }
  }
  EXPECT_GT(found, 250u);  // some points lie in the margin around the TIN, or in its void
}

TEST(HierarchyLocator, ThreadsShareOneLocator) {
  const Hierarchy h = buildFrom(test::smallSyntheticDem());
  const HierarchyLocator locator(h);
  const auto points = randomPoints(h.base, 4000, 99);
  std::vector<LocatedPoint> alone, shared(points.size());
  for (const auto& [x, y] : points) alone.push_back(locator.locate(x, y, 1));
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < 4; ++k)
    threads.emplace_back([&, k] {
      for (std::size_t i = k; i < points.size(); i += 4) shared[i] = locator.locate(points[i][0], points[i][1], 1);
    });
  for (std::thread& t : threads) t.join();
  for (std::size_t i = 0; i < points.size(); ++i) {
    ASSERT_EQ(shared[i].triangle, alone[i].triangle) << "point " << i;
    if (alone[i].found()) {
      EXPECT_EQ(shared[i].z, alone[i].z) << "point " << i;
    }
  }
}

// A star whose triangles do not surround its vertex (as a corrupt file could give) is
// refused when the locator is made, not met in the middle of a search.
TEST(HierarchyLocator, InconsistentHierarchyIsRefused) {
  Hierarchy h = buildFrom(test::smallSyntheticDem());
  ASSERT_GE(h.groups.size(), 2u);
  const Group& first = h.groups.front();
  const TinVertex& v = h.base.vertices[first.vertex];
  const auto far = std::find_if(h.groups.begin(), h.groups.end(), [&](const Group& g) {
    const TinVertex& u = h.base.vertices[g.vertex];
    return std::hypot(u.x - v.x, u.y - v.y) > 2000;
  });
  ASSERT_NE(far, h.groups.end());
  h.links[first.acceptBegin] = h.links[far->acceptBegin];
  try {
    const HierarchyLocator locator(h);
    FAIL() << "no error for a star with a triangle from elsewhere";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("inconsistent"), std::string::npos) << e.what();
  }
}

TEST(HierarchyLocator, LevelOutsideTheHierarchyThrows) {
  const Hierarchy h = buildFrom(test::smallSyntheticDem());
  const HierarchyLocator locator(h);
  const TinVertex& v = h.base.vertices.front();
  EXPECT_THROW(locator.locate(v.x, v.y, -1), Error);
  EXPECT_NO_THROW(locator.locate(v.x, v.y, h.coarsest()));
  try {
    locator.locate(v.x, v.y, h.coarsest() + 1);
    FAIL() << "no error for level " << h.coarsest() + 1;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("levels 0 to " + std::to_string(h.coarsest())), std::string::npos) << e.what();
  }
}

TEST(HierarchyLocator, RealDemAgreesWithBruteForce) {
  const std::string dir = test::dataDir();
  if (dir.empty()) GTEST_SKIP() << "../shared/data is absent (set TINLOD_TEST_DATA): real-DEM test skipped";
  const Dem dem = readDem(dir + "/dead_sea_N31E035.tif", 1, kQuiet);
  SampleOptions so;
  so.block = 6;  // 40 k vertices keep the brute force quick
  const Hierarchy h = buildFrom(dem, so);
  const HierarchyLocator locator(h);
  const auto points = randomPoints(h.base, 2000, 2024);
  for (std::int32_t level : {0, 1, h.coarsest() / 2, h.coarsest()}) {
    const Agreement a = expectAgreement(h, locator, level, points);
    EXPECT_GT(a.found, points.size() / 2);
  }
}

// swiss_alps' bottom row at the coarsest level: straight edges between vertices 274 cells
// apart cut 294 of its valid centres off (by up to 6 m, beyond the reach); a raster edge
// is now cut inside by at most 5 % of a cell, and only the centres level 0 misses (one
// cell wide beside voids) stay off the TIN.
TEST(HierarchyLocator, TheCoarsestLevelOfARealDemInDegreesKeepsItsEdgeCentres) {
  const std::string dir = test::dataDir();
  if (dir.empty()) GTEST_SKIP() << "../shared/data is absent (set TINLOD_TEST_DATA): real-DEM test skipped";
  const Dem dem = readDem(dir + "/swiss_alps_N46E008.tif", 1, kQuiet);
  const Hierarchy h = buildFrom(dem);
  const HierarchyLocator locator(h);
  std::vector<double> x, y;
  for (int c = 0; c < dem.width; ++c)
    if (dem.valid(dem.height - 1, c)) {
      x.push_back(dem.geotransform[0] + (c + 0.5) * dem.geotransform[1]);
      y.push_back(dem.geotransform[3] + (dem.height - 0.5) * dem.geotransform[5]);
    }
  CrsTransform::forDem(dem, "", "", kQuiet).apply(x, y);
  std::size_t atZero = 0, atCoarsest = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    atZero += !locator.locate(x[i], y[i], 0).found();
    atCoarsest += !locator.locate(x[i], y[i], h.coarsest()).found();
  }
  EXPECT_GT(x.size(), 1000u);
  EXPECT_LT(atZero, 60u);
  EXPECT_LE(atCoarsest, atZero + 10) << "of " << x.size() << " bottom-row centres at level " << h.coarsest();
}

}  // namespace
}  // namespace tinlod
