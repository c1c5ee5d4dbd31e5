// SPDX-License-Identifier: GPL-3.0-or-later
#include "grid_bend.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "test_support.h"
#include "tinlod/crs_transform.h"
#include "tinlod/sample_job.h"

namespace tinlod {
namespace {

struct BentTin {
  Dem dem;
  Tin tin;
  std::string targetSrs;
};

// Large triangles (one cell in 36 sampled) over rough hills, in degrees, read in `targetSrs`.
BentTin bentTin(double lon0, double lat0, double cell, int width, int height, const std::string& targetSrs) {
  BentTin out{test::makeDem(width, height, 1, [&](int r, int c) {
                return float(900 + 700 * std::sin(5.0 * c / width) * std::cos(3.0 * r / height) + 30 * std::sin(r * 1.7 + c));
              }),
              {},
              targetSrs};
  out.dem.geotransform = {lon0, cell, 0, lat0, 0, -cell};
  out.dem.crsWkt = test::wktOf(4326);
  SampleOptions options;
  options.block = 6;
  options.targetSrs = targetSrs;
  out.tin = sampleTin(out.dem, options, ProgressRange(Feedback{}, 0, 1));
  return out;
}

// Each triangle's gap, measured here with PROJ at every centre.
std::vector<double> exactGaps(const BentTin& b, const CrsTransform& toTin) {
  std::vector<double> x, y;
  for (const Triangle& t : b.tin.triangles) {
    double col = 0, row = 0;
    for (VertexId v : t) col += (b.tin.vertices[v].col + 0.5 + b.tin.vertices[v].dcol) / 3, row += (b.tin.vertices[v].row + 0.5 + b.tin.vertices[v].drow) / 3;
    x.push_back(b.dem.geotransform[0] + col * b.dem.geotransform[1]);
    y.push_back(b.dem.geotransform[3] + row * b.dem.geotransform[5]);
  }
  toTin.apply(x, y);
  std::vector<double> gaps;
  for (std::size_t i = 0; i < b.tin.triangles.size(); ++i) {
    const TinVertex &p = b.tin.vertices[b.tin.triangles[i][0]], &q = b.tin.vertices[b.tin.triangles[i][1]],
                    &r = b.tin.vertices[b.tin.triangles[i][2]];
    // The plane through the corners in the CRS, at the centre's place there.
    const double ux = q.x - p.x, uy = q.y - p.y, uz = q.z - p.z, vx = r.x - p.x, vy = r.y - p.y, vz = r.z - p.z;
    const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    const double z = p.z - (nx * (x[i] - p.x) + ny * (y[i] - p.y)) / nz;
    gaps.push_back(std::fabs(z - (p.z + q.z + r.z) / 3));
  }
  return gaps;
}

TEST(GridBend, NoTrianglesHeightsPartByMoreThanItsBound) {
  const struct {
    const char* name;
    BentTin tin;
  } cases[] = {
      {"the Alps in UTM", bentTin(7.0, 47.5, 0.01, 200, 150, "EPSG:32632")},
      {"Scandinavia in world Mercator", bentTin(0, 80, 0.25, 160, 80, "EPSG:3395")},
      {"a quarter of the Arctic in a polar stereographic", bentTin(0, 85, 0.5, 180, 50, "EPSG:3413")},
  };
  for (const auto& c : cases) {
    const CrsTransform toTin = CrsTransform::forDem(c.tin.dem, "", c.tin.targetSrs, ProgressRange(Feedback{}, 0, 1));
    const double bend = bendBound(c.tin.dem, toTin);
    ASSERT_TRUE(std::isfinite(bend) && bend > 0) << c.name << ": " << bend;
    const std::vector<double> gaps = exactGaps(c.tin, toTin);
    std::size_t tight = 0;
    for (std::size_t i = 0; i < gaps.size(); ++i) {
      const Triangle& t = c.tin.tin.triangles[i];
      const double bound = heightGapBound(c.tin.tin.vertices[t[0]], c.tin.tin.vertices[t[1]], c.tin.tin.vertices[t[2]], bend);
      EXPECT_LE(gaps[i], bound) << c.name << ", triangle " << i;
      tight += gaps[i] > bound / 10;
    }
    // A bound that is no use would measure every triangle.
    EXPECT_GT(tight, 0u) << c.name;
    // What the check reports is the largest gap whenever it is over the floor, from the
    // triangles the bound cannot clear alone.
    const double largest = *std::max_element(gaps.begin(), gaps.end());
    const TriangleAt at = [&](std::size_t i) -> const Triangle& { return c.tin.tin.triangles[i]; };
    const HeightGap found = heightGap(c.tin.dem, toTin, c.tin.tin.vertices, gaps.size(), at, largest / 2);
    EXPECT_NEAR(found.metres, largest, 1e-9 * largest) << c.name;
    EXPECT_LT(found.measured, gaps.size()) << c.name;
    EXPECT_EQ(heightGap(c.tin.dem, toTin, c.tin.tin.vertices, gaps.size(), at, 0).measured, gaps.size()) << c.name;
  }
}

TEST(GridBend, AFineTinInUtmIsNotMeasuredTriangleByTriangle) {
  // 240 x 240 cells of 1/1200 degree at 47 N, whose triangles part by 7 mm at most: none can
  // part by 5 cm, so PROJ is spared their centres (it took 8.7 % of an insert of 6.6 M triangles).
  const BentTin fine = bentTin(7.0, 47.5, 1.0 / 1200, 240, 240, "EPSG:32632");
  const CrsTransform toTin = CrsTransform::forDem(fine.dem, "", fine.targetSrs, ProgressRange(Feedback{}, 0, 1));
  const TriangleAt at = [&](std::size_t i) -> const Triangle& { return fine.tin.triangles[i]; };
  const HeightGap found = heightGap(fine.dem, toTin, fine.tin.vertices, fine.tin.triangles.size(), at, 0.05);
  EXPECT_EQ(found.measured, 0u);
  const std::vector<double> gaps = exactGaps(fine, toTin);
  EXPECT_LT(*std::max_element(gaps.begin(), gaps.end()), 0.05);
}

TEST(GridBend, ACrsThatIsTheGridsUpToRoundingIsNotMeasuredTriangleByTriangle) {
  // ETRS89 / UTM 32N read in WGS 84 / UTM 32N: its second differences are rounding noise,
  // which the lattice's jump test took for a bend it could not follow (PROJ on every centre).
  Dem dem = test::makeDem(300, 300, 25, [](int r, int c) { return float(500 + 300 * std::sin(c / 30.0) * std::cos(r / 40.0)); });
  dem.geotransform = {480000, 25, 0, 5200000, 0, -25};
  dem.crsWkt = test::wktOf(25832);
  SampleOptions options;
  options.targetSrs = "EPSG:32632";
  const Tin tin = sampleTin(dem, options, ProgressRange(Feedback{}, 0, 1));
  const CrsTransform toTin = CrsTransform::forDem(dem, "", "EPSG:32632", ProgressRange(Feedback{}, 0, 1));
  ASSERT_FALSE(toTin.isIdentity());
  EXPECT_TRUE(std::isfinite(bendBound(dem, toTin)));
  const TriangleAt at = [&](std::size_t i) -> const Triangle& { return tin.triangles[i]; };
  EXPECT_EQ(heightGap(dem, toTin, tin.vertices, tin.triangles.size(), at, 0.01).measured, 0u);
}

TEST(GridBend, TheDemsOwnCrsDoesNotBend) {
  Dem dem = test::makeDem(50, 40, 30, [](int r, int c) { return float(r + c); });
  dem.crsWkt = test::wktOf(32632);
  EXPECT_EQ(bendBound(dem, CrsTransform::forDem(dem, "", "", ProgressRange(Feedback{}, 0, 1))), 0);
}

}  // namespace
}  // namespace tinlod
