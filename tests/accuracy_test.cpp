// SPDX-License-Identifier: GPL-3.0-or-later
// Interpolation, the evaluator, the accuracy raster and the accuracy job, end to end.
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "test_support.h"
#include "tinlod/accuracy_job.h"
#include "tinlod/build_job.h"
#include "tinlod/error.h"
#include "tinlod/hierarchy_builder.h"
#include "tinlod/hierarchy_reader.h"
#include "tinlod/sample_job.h"
#include "tinlod/tin_rasterizer.h"
#include "tinlod/synthetic_dem.h"

namespace fs = std::filesystem;

namespace tinlod {
namespace {

const ProgressRange kQuiet(Feedback{}, 0, 1);

const VariableComparison& variable(const LevelAccuracy& row, const std::string& name) {
  const VariableComparison* v = findVariable(row, name);
  if (!v) throw Error("no variable " + name);
  return *v;
}

TEST(TinRasterizer, TwoTrianglesReproduceTheirPlaneAtEveryCoveredPointAndNoOther) {
  // A square from (1.5, 1.5) to (7.5, 5.5) in test-point units, split along a diagonal.
  const std::vector<std::array<double, 2>> pos{{1.5, 1.5}, {7.5, 1.5}, {7.5, 5.5}, {1.5, 5.5}};
  std::vector<double> z;
  for (const auto& p : pos) z.push_back(2 * p[0] - 3 * p[1] + 10);
  const Grid g = rasterizeTin(pos, z, {{0, 1, 2}, {0, 2, 3}}, 10, 8, kQuiet);
  int covered = 0;
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.cols; ++c)
      if (g.valid(c, r)) {
        ++covered;
        EXPECT_NEAR(g.at(c, r), 2 * c - 3 * r + 10, 1e-12);
      }
  EXPECT_EQ(covered, 6 * 4);  // columns 2..7, rows 2..5
}

TEST(TinRasterizer, PointsOnSharedEdgesAndVerticesAreNeverMissed) {
  // Vertices exactly on test points: a 4 x 4 lattice of squares, split both ways.
  std::vector<std::array<double, 2>> pos;
  std::vector<double> z;
  for (int r = 0; r <= 4; ++r)
    for (int c = 0; c <= 4; ++c) pos.push_back({2.0 * c, 2.0 * r}), z.push_back(c * r);
  std::vector<Triangle> tris;
  for (VertexId r = 0; r < 4; ++r)
    for (VertexId c = 0; c < 4; ++c) {
      const VertexId a = r * 5 + c, b = a + 1, d = a + 5, e = d + 1;
      if ((r + c) % 2) tris.push_back({a, b, e}), tris.push_back({a, e, d});
      else tris.push_back({a, b, d}), tris.push_back({b, e, d});
    }
  const Grid g = rasterizeTin(pos, z, tris, 9, 9, kQuiet);
  for (double v : g.values) EXPECT_FALSE(std::isnan(v));
}

TEST(TinRasterizer, AWindowOfTheGridHasTheWholeGridsValuesToTheBit) {
  // A random TIN over 60 x 50 points, its vertices at fractional places and tiny heights
  // beside large ones, so that rounding differs from triangle to triangle.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::array<double, 2>> pos;
  std::vector<double> z;
  for (int r = 0; r <= 10; ++r)
    for (int c = 0; c <= 12; ++c) {
      pos.push_back({-0.5 + c * 5.0 + (c > 0 && c < 12 ? 3 * u(rng) - 1.5 : 0), -0.5 + r * 5.0 + (r > 0 && r < 10 ? 3 * u(rng) - 1.5 : 0)});
      z.push_back(1000 * u(rng) + 1e-7 * u(rng));
    }
  std::vector<Triangle> tris;
  for (VertexId r = 0; r < 10; ++r)
    for (VertexId c = 0; c < 12; ++c) {
      const VertexId a = r * 13 + c, b = a + 1, d = a + 13, e = d + 1;
      tris.push_back({a, b, e}), tris.push_back({a, e, d});
    }
  const Grid whole = rasterizeTin(pos, z, tris, 60, 50, kQuiet);
  for (const auto& [col0, row0, cols, rows] : {std::array<int, 4>{17, 23, 20, 11}, std::array<int, 4>{0, 0, 60, 50},
                                               std::array<int, 4>{40, 3, 20, 47}, std::array<int, 4>{59, 49, 1, 1}}) {
    const Grid window = rasterizeTin(pos, z, tris, cols, rows, kQuiet, col0, row0);
    std::size_t differing = 0, valid = 0;
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) {
        const double a = window.at(c, r), b = whole.at(col0 + c, row0 + r);
        valid += !std::isnan(b);
        differing += std::isnan(a) != std::isnan(b) || (!std::isnan(b) && a != b);
      }
    EXPECT_EQ(differing, 0u) << "window at " << col0 << ", " << row0;
    EXPECT_EQ(valid, std::size_t(cols) * rows) << "the TIN covers every point";
  }
}

// A sliver whose near-horizontal edge lies a hair across row 0 (as a geographic DEM's
// transformed corners do): the edge's tolerance takes the points along it on that row,
// though the row meets the other two edges near one end only.
TEST(TinRasterizer, PointsWithinToleranceOfANearlyHorizontalEdgeAreFilled) {
  const std::vector<std::array<double, 2>> pos{
      {68.005793268800616, -1.2313483566117611e-12}, {71.000901066284214, 1.9969538147631805}, {71.00644036148951, 7.2951644725094411e-12}};
  std::vector<double> z;
  for (const auto& p : pos) z.push_back(2 * p[0] - 3 * p[1] + 10);
  const Grid g = rasterizeTin(pos, z, {{0, 1, 2}}, 80, 4, kQuiet);
  for (int c = 69; c <= 71; ++c) {
    ASSERT_TRUE(g.valid(c, 0)) << c;
    EXPECT_NEAR(g.at(c, 0), 2 * c + 10, 1e-6) << c;
  }
  EXPECT_TRUE(g.valid(71, 1));
  EXPECT_FALSE(g.valid(68, 0));
  EXPECT_FALSE(g.valid(72, 0));
}

// Corners far beyond the range of int (a vertex a CRS could not transform, or a crafted
// file's) fill only the points they cover, and leave the others; the sanitizer build sees
// that no conversion to int overflows on the way.
TEST(TinRasterizer, TrianglesFarOffTheGridOrWithNonFiniteCornersDoNoHarm) {
  const double inf = INFINITY;
  const std::vector<std::array<double, 2>> pos{{1.5, 1.5}, {7.5, 1.5}, {7.5, 5.5}, {-1e11, -1e11}, {1e11, 3},
                                               {4, 1e11}, {inf, 2}, {NAN, 3}};
  const std::vector<double> z(pos.size(), 5.0);
  // One ordinary triangle, one that covers the whole grid and beyond, one with an infinite
  // and one with a NaN corner.
  const Grid g = rasterizeTin(pos, z, {{0, 1, 2}, {3, 4, 5}, {0, 1, 6}, {1, 2, 7}}, 10, 8, kQuiet);
  for (double v : g.values) EXPECT_NEAR(v, 5.0, 1e-6);
}

struct Fixture {
  Dem dem = test::smallSyntheticDem();
  Tin tin = sampleTin(dem, {}, kQuiet);
  CrsTransform toTin = CrsTransform::forDem(dem, "", "", kQuiet);
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

TEST(AccuracyEvaluator, TheOriginalAgainstItselfIsPerfect) {
  const Fixture& f = fixture();
  const AccuracyEvaluator e(f.dem, f.tin, f.toTin, {}, kQuiet);
  LevelAccuracy row;
  // The strips in order, each as wide as the grid, together as tall.
  int rows = 0, strips = 0;
  const BandStrips bands = [&](const AccuracyBands& strip, int row0) {
    EXPECT_EQ(row0, rows);
    for (const Grid* g : {&strip.elevationDifference, &strip.meanCurvatureDifference, &strip.meanCurvatureReference,
                          &strip.meanCurvatureSimplified}) {
      EXPECT_EQ(g->cols, e.grid().cols);
      EXPECT_EQ(g->rows, strip.elevationDifference.rows);
    }
    for (double v : strip.elevationDifference.values) EXPECT_TRUE(std::isnan(v) || v == 0);
    rows += strip.elevationDifference.rows, ++strips;
  };
  e.evaluate(f.tin.triangles, row, &bands, kQuiet);
  EXPECT_GT(row.testPoints, 80000u);
  EXPECT_EQ(row.rmse, 0);
  EXPECT_EQ(row.maxAbsError, 0);
  EXPECT_NEAR(variable(row, "elevation").correlation, 1, 1e-12);
  EXPECT_NEAR(variable(row, "mean_curvature").correlation, 1, 1e-12);
  EXPECT_NEAR(variable(row, "aspect").correlation, 1, 1e-9);
  EXPECT_EQ(rows, e.grid().rows);
  EXPECT_EQ(strips, (e.grid().rows + 255) / 256);
}

TEST(AccuracyEvaluator, RaisingEveryHeightByTwoMetresGivesAnRmseOfTwoAndPerfectCorrelation) {
  const Fixture& f = fixture();
  std::vector<double> raised;
  for (const TinVertex& v : f.tin.vertices) raised.push_back(v.z + 2);
  const AccuracyEvaluator e(f.dem, f.tin, f.toTin, {}, kQuiet);
  LevelAccuracy row;
  e.evaluate(raised, f.tin.triangles, row, nullptr, kQuiet);
  EXPECT_NEAR(row.rmse, 2, 1e-9);
  EXPECT_NEAR(row.meanError, 2, 1e-9);
  EXPECT_NEAR(row.maxAbsError, 2, 1e-9);
  const VariableComparison& z = variable(row, "elevation");
  EXPECT_NEAR(z.correlation, 1, 1e-12);
  EXPECT_NEAR(z.meanSimplified - z.meanReference, 2, 1e-9);
  EXPECT_NEAR(z.stdSimplified, z.stdReference, 1e-9);
  EXPECT_NEAR(variable(row, "mean_curvature").correlation, 1, 1e-12);
}

TEST(AccuracyEvaluator, TheDemAsReferenceOfAFlatDemGivesNoError) {
  const Dem flat = test::makeDem(90, 60, 10, [](int, int) { return 123.5f; });
  const Tin tin = sampleTin(flat, {}, kQuiet);
  const CrsTransform toTin = CrsTransform::forDem(flat, "", "", kQuiet);
  AccuracyOptions o;
  o.reference = Reference::Dem;
  const AccuracyEvaluator e(flat, tin, toTin, o, kQuiet);
  LevelAccuracy row;
  e.evaluate(tin.triangles, row, nullptr, kQuiet);
  EXPECT_GT(row.testPoints, 4000u);
  EXPECT_NEAR(row.rmse, 0, 1e-9);
  EXPECT_NEAR(variable(row, "mean_curvature").meanReference, 0, 1e-12);
}

TEST(AccuracyEvaluator, ABadStepOrControlSpacingIsRefusedByName) {
  AccuracyOptions o;
  o.step = 0;
  EXPECT_THROW(o.validate(), Error);
  o.step = 1, o.controlSpacing = 0;
  try {
    o.validate();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("-control"), std::string::npos);
  }
}

}  // namespace
}  // namespace tinlod
