// SPDX-License-Identifier: GPL-3.0-or-later
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <random>

#include "mesh_checks.h"
#include "test_support.h"
#include "tinlod/dem_reader.h"
#include "tinlod/error.h"
#include "tinlod/gpkg_writer.h"
#include "tinlod/greedy_inserter.h"
#include "tinlod/grid.h"
#include "tinlod/insert_job.h"
#include "tinlod/sample_job.h"
#include "tinlod/synthetic_dem.h"
#include "tinlod/triangulation.h"

namespace fs = std::filesystem;

namespace tinlod {
namespace {

const ProgressRange kQuiet(Feedback{}, 0, 1);
// Errors are computed in double from float heights: a cell exactly at the tolerance (whole
// metres of SRTM and a whole tolerance) may measure a hair over it.
constexpr double kRounding = 1e-9;

// Brute force, apart from the code under test: every valid cell against every triangle
// whose box holds it, barycentric in grid units (vertices at their cells' centres).
struct BruteForce {
  double maxError = 0;
  std::size_t covered = 0, uncovered = 0;
};
BruteForce bruteForce(const Dem& dem, const Tin& tin) {
  Grid heights(dem.width, dem.height);
  for (const Triangle& t : tin.triangles) {
    double x[3], y[3], z[3];
    for (int k = 0; k < 3; ++k) x[k] = tin.vertices[t[k]].col, y[k] = tin.vertices[t[k]].row, z[k] = tin.vertices[t[k]].z;
    const double det = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
    for (int r = int(std::min({y[0], y[1], y[2]})); r <= int(std::max({y[0], y[1], y[2]})); ++r)
      for (int c = int(std::min({x[0], x[1], x[2]})); c <= int(std::max({x[0], x[1], x[2]})); ++c) {
        const double w0 = ((x[1] - c) * (y[2] - r) - (y[1] - r) * (x[2] - c)) / det;
        const double w1 = ((x[2] - c) * (y[0] - r) - (y[2] - r) * (x[0] - c)) / det;
        const double w2 = 1 - w0 - w1;
        if (w0 >= -1e-12 && w1 >= -1e-12 && w2 >= -1e-12) heights.at(c, r) = w0 * z[0] + w1 * z[1] + w2 * z[2];
      }
  }
  BruteForce out;
  for (int r = 0; r < dem.height; ++r)
    for (int c = 0; c < dem.width; ++c) {
      if (!dem.valid(r, c)) continue;
      if (std::isnan(heights.at(c, r))) {
        ++out.uncovered;
        continue;
      }
      ++out.covered;
      out.maxError = std::max(out.maxError, std::fabs(heights.at(c, r) - dem.at(r, c)));
    }
  return out;
}

// The TIN on its DEM's grid at a ground scale: where a geographic DEM's TIN is Delaunay.
Tin groundGrid(Tin tin, double cellWidth, double cellHeight) {
  for (TinVertex& v : tin.vertices) v.x = v.col * cellWidth, v.y = -v.row * cellHeight;
  return tin;
}

InsertedTin insert(const Dem& dem, double maxError, std::size_t maxVertices = 0) {
  InsertOptions o;
  o.maxError = maxError;
  o.maxVertices = maxVertices;
  return greedyInsertionTin(dem, o, kQuiet);
}

// Rolling terrain with a little noise, 30 m cells.
Dem hills(int width, int height) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> noise(0, 0.3f);
  return test::makeDem(width, height, 30, [&](int r, int c) {
    return float(200 + 80 * std::sin(c * 0.05) * std::cos(r * 0.04) + 6 * std::sin(c * 0.3 + r * 0.2)) + noise(rng);
  });
}

TEST(GreedyInsertion, PlaneNeedsOnlyTheCorners) {
  const Dem dem = test::makeDem(120, 90, 10, [](int r, int c) { return float(100 + 0.5 * c - 0.25 * r); });
  const InsertedTin out = insert(dem, 1e-6);
  EXPECT_EQ(out.tin.vertices.size(), 4u);
  EXPECT_EQ(out.tin.triangles.size(), 2u);
  EXPECT_LT(out.summary.measuredMaxError, 1e-6);
  EXPECT_EQ(out.summary.measuredCells, 120u * 90u);
  for (const TinVertex& v : out.tin.vertices) {
    EXPECT_TRUE(v.row == 0 || v.row == 89);
    EXPECT_TRUE(v.col == 0 || v.col == 119);
  }
}

TEST(GreedyInsertion, SingleSpikeIsInsertedFirst) {
  const Dem dem = test::makeDem(101, 81, 10, [](int r, int c) { return r == 30 && c == 70 ? 50.f : 0.f; });
  const InsertedTin out = insert(dem, 0.5);
  const auto fifth = std::find(out.insertion.begin(), out.insertion.end(), 5u);
  ASSERT_NE(fifth, out.insertion.end());
  const std::size_t i = std::size_t(fifth - out.insertion.begin());
  EXPECT_EQ(out.tin.vertices[i].row, 30);
  EXPECT_EQ(out.tin.vertices[i].col, 70);
  EXPECT_DOUBLE_EQ(out.errorBefore[i], 50);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_TRUE(std::isnan(out.errorBefore[std::find(out.insertion.begin(), out.insertion.end(), k + 1) - out.insertion.begin()]));
  EXPECT_LE(bruteForce(dem, out.tin).maxError, 0.5);
}

TEST(GreedyInsertion, ToleranceHoldsAtEveryCellByBruteForce) {
  const Dem dem = hills(300, 220);
  for (double tol : {0.5, 2.0, 10.0}) {
    const InsertedTin out = insert(dem, tol);
    const BruteForce b = bruteForce(dem, out.tin);
    EXPECT_EQ(b.uncovered, 0u);
    EXPECT_EQ(b.covered, 300u * 220u);
    EXPECT_LE(b.maxError, tol + kRounding) << tol;
    EXPECT_NEAR(b.maxError, out.summary.measuredMaxError, 1e-9);
    EXPECT_LE(out.summary.maxError, tol);
    // The largest error left, though triangles below the tolerance are never queued.
    EXPECT_NEAR(out.summary.maxError, b.maxError, 1e-9) << tol;
    EXPECT_EQ(test::delaunayViolations(out.tin), 0u);
    EXPECT_EQ(test::clockwiseTriangles(out.tin), 0u);
    EXPECT_EQ(out.tin.triangles.size(), out.summary.triangles);
  }
}

// The triangles come out in blocks of 16 x 16 cells, block row by block row, not in the
// order CGAL made them (all over the grid): neighbours in the list are neighbours on the map.
TEST(GreedyInsertion, TrianglesComeOutAreaByArea) {
  const Dem dem = hills(300, 220);
  const InsertedTin out = insert(dem, 0.5);
  ASSERT_GT(out.tin.triangles.size(), 5000u);
  const auto centre = [&out](const Triangle& t, bool row) {
    double sum = 0;
    for (VertexId v : t) sum += row ? out.tin.vertices[v].row : out.tin.vertices[v].col;
    return sum / 3;
  };
  double step = 0, rowsBack = 0;
  for (std::size_t i = 1; i < out.tin.triangles.size(); ++i) {
    const Triangle &a = out.tin.triangles[i - 1], &b = out.tin.triangles[i];
    step += std::hypot(centre(b, false) - centre(a, false), centre(b, true) - centre(a, true));
    rowsBack = std::max(rowsBack, centre(a, true) - centre(b, true));
  }
  // In the order of making, a step is a third of the grid on average (about 100 cells).
  EXPECT_LT(step / double(out.tin.triangles.size() - 1), 8.0);
  // Never back more than a block and the triangles' reach above it.
  EXPECT_LT(rowsBack, 40.0);
}

// A run at a finer tolerance than the one before goes on as one run at that tolerance
// would have: the triangles the coarser run left out of its queue are queued again.
TEST(GreedyInsertion, AFinerRunAfterACoarserOneIsOneFineRun) {
  const Dem dem = hills(200, 150);
  InsertGrid grid;
  grid.cols = dem.width, grid.rows = dem.height, grid.z = dem.z.data();
  GreedyInserter twice(grid, kQuiet), once(grid, kQuiet);
  twice.run({10, 0, 0}, kQuiet);
  const std::size_t coarse = twice.vertexCount();
  EXPECT_LE(twice.maxError(), 10);
  EXPECT_GT(twice.maxError(), 5);
  twice.run({1, 0, 0}, kQuiet);
  once.run({1, 0, 0}, kQuiet);
  EXPECT_GT(twice.vertexCount(), 2 * coarse);
  ASSERT_EQ(twice.inserted().size(), once.inserted().size());
  for (std::size_t i = 0; i < once.inserted().size(); ++i) {
    ASSERT_EQ(twice.inserted()[i].candidate, once.inserted()[i].candidate) << i;
    ASSERT_TRUE(twice.inserted()[i].errorBefore == once.inserted()[i].errorBefore ||
                std::isnan(once.inserted()[i].errorBefore)) << i;
  }
  EXPECT_EQ(twice.maxError(), once.maxError());
}

TEST(GreedyInsertion, LastRowAndColumnAreCandidatesToo) {
  // Flat but for ridges along the last row and the last column.
  const Dem dem = test::makeDem(80, 60, 10, [](int r, int c) { return float((c == 79 ? 5 * std::sin(r * 0.3) : 0) + (r == 59 ? 3 * std::cos(c * 0.2) : 0)); });
  const InsertedTin out = insert(dem, 0.1);
  EXPECT_LE(bruteForce(dem, out.tin).maxError, 0.1);
  EXPECT_GT(out.tin.vertices.size(), 20u);
}

TEST(GreedyInsertion, VertexLimitGivesExactlyThatCount) {
  const Dem dem = hills(200, 150);
  for (std::size_t n : {4u, 5u, 137u, 1000u}) {
    const InsertedTin out = insert(dem, 0, n);
    EXPECT_EQ(out.tin.vertices.size(), n);
    EXPECT_EQ(out.tin.triangles.size(), 2 * n - 2 - [&] {  // Euler for a triangulated convex polygon
      std::size_t hull = 0;
      for (const TinVertex& v : out.tin.vertices) hull += v.outline;
      return hull;
    }());
  }
}

TEST(GreedyInsertion, TriangleLimitIsNeverExceeded) {
  const Dem dem = hills(200, 150);
  InsertOptions o;
  o.maxError = 0;
  o.maxTriangles = 501;
  const InsertedTin out = greedyInsertionTin(dem, o, kQuiet);
  EXPECT_LE(out.tin.triangles.size(), 501u);
  EXPECT_GE(out.tin.triangles.size(), 499u);
}

TEST(GreedyInsertion, HolesStayHolesAndEveryValidCellIsCovered) {
  const Dem dem = test::smallSyntheticDem();  // with a lake and a nodata void
  ASSERT_LT(dem.validCount(), std::size_t(dem.width) * dem.height);
  const InsertedTin out = insert(dem, 1);
  EXPECT_EQ(test::trianglesOverNodata(dem, out.tin), 0u);
  EXPECT_EQ(test::verticesOnNodata(dem, out.tin), 0u);
  const BruteForce b = bruteForce(dem, out.tin);
  EXPECT_EQ(b.uncovered, out.summary.uncoveredCells);
  EXPECT_LE(b.uncovered, 50u);  // only cells of one-cell-wide slivers of data the TIN cannot hold
  EXPECT_LE(b.maxError, 1.0);
  EXPECT_FALSE(out.summary.holesOpen);
  const test::Topology topo = test::analyseTopology(out.tin);
  EXPECT_EQ(topo.problem, "");
  EXPECT_GE(topo.boundaryLoops, 2u);  // the outline and the void
  // A vertex is on the outline exactly when it ends an edge that only one triangle has.
  std::map<std::pair<VertexId, VertexId>, int> edgeUses;
  for (const Triangle& t : out.tin.triangles)
    for (int k = 0; k < 3; ++k) ++edgeUses[std::minmax(t[k], t[(k + 1) % 3])];
  std::vector<bool> onOutline(out.tin.vertices.size(), false);
  for (const auto& [edge, uses] : edgeUses)
    if (uses == 1) onOutline[edge.first] = onOutline[edge.second] = true;
  std::size_t outline = 0;
  for (std::size_t i = 0; i < onOutline.size(); ++i) {
    EXPECT_EQ(out.tin.vertices[i].outline, onOutline[i]) << "vertex " << i;
    outline += onOutline[i];
  }
  EXPECT_GT(outline, 8u);
}

TEST(GreedyInsertion, SameInputSameTin) {
  const Dem dem = test::smallSyntheticDem();
  const InsertedTin a = insert(dem, 2), b = insert(dem, 2);
  ASSERT_EQ(a.tin.triangles.size(), b.tin.triangles.size());
  EXPECT_EQ(a.tin.triangles, b.tin.triangles);
  EXPECT_EQ(a.insertion, b.insertion);
}

// Sampled candidates are jittered, so no four are cocircular and the Delaunay TIN of a
// prefix of the insertion order is unique: its maximum error over the candidates must be
// the next vertex's error_before.
TEST(GreedyInsertion, EveryPrefixIsATinOfTheRecordedError) {
  const Dem dem = hills(150, 120);
  InsertOptions o;
  o.candidates = InsertCandidates::Samples;
  o.maxError = 1;
  const InsertedTin out = greedyInsertionTin(dem, o, kQuiet);
  const Tin sampled = sampleTin(dem, o.sample, kQuiet);
  std::vector<std::size_t> byOrder(out.insertion.size());
  for (std::size_t i = 0; i < out.insertion.size(); ++i) byOrder[out.insertion[i] - 1] = i;
  std::size_t hull = 0;
  for (double e : out.errorBefore) hull += std::isnan(e);
  for (std::size_t k : {hull, hull + 7, hull + 60, hull + 300}) {
    ASSERT_LT(k, byOrder.size());
    std::vector<TinVertex> prefix;
    for (std::size_t j = 0; j < k; ++j) prefix.push_back(out.tin.vertices[byOrder[j]]);
    Tin coarse;
    coarse.vertices = prefix;
    coarse.triangles = delaunayTriangles(prefix, kQuiet).triangles;
    double worst = 0;
    for (const TinVertex& s : sampled.vertices)
      for (const Triangle& t : coarse.triangles) {
        const TinVertex &a = prefix[t[0]], &b = prefix[t[1]], &c = prefix[t[2]];
        const double det = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        const double w0 = ((b.x - s.x) * (c.y - s.y) - (b.y - s.y) * (c.x - s.x)) / det;
        const double w1 = ((c.x - s.x) * (a.y - s.y) - (c.y - s.y) * (a.x - s.x)) / det;
        const double w2 = 1 - w0 - w1;
        if (w0 < -1e-12 || w1 < -1e-12 || w2 < -1e-12) continue;
        worst = std::max(worst, std::fabs(w0 * a.z + w1 * b.z + w2 * c.z - s.z));
        break;
      }
    EXPECT_NEAR(worst, out.errorBefore[byOrder[k]], 1e-6) << "prefix of " << k;
  }
}

TEST(GreedyInsertion, SampledCandidatesAreTheSampledTinsVertices) {
  const Dem dem = test::smallSyntheticDem();
  InsertOptions o;
  o.candidates = InsertCandidates::Samples;
  o.maxError = 0;
  const Tin sampled = sampleTin(dem, o.sample, kQuiet);
  const InsertedTin all = greedyInsertionTin(dem, o, kQuiet);
  EXPECT_EQ(all.summary.candidates, sampled.vertices.size());
  // Run to exactness, every sample whose error is not zero is a vertex.
  EXPECT_LE(all.tin.vertices.size(), sampled.vertices.size());
  EXPECT_GT(all.tin.vertices.size(), sampled.vertices.size() / 2);
  EXPECT_EQ(test::trianglesOverNodata(dem, all.tin), 0u);
  // No sliver along the straight raster edges (their jittered points are not collinear):
  // the TIN covers the cells the sampled TIN covers, and a 10 m tolerance holds at them.
  const Tin& tin = sampled;
  const BruteForce ours = bruteForce(dem, all.tin), theirs = bruteForce(dem, tin);
  EXPECT_NEAR(double(ours.covered), double(theirs.covered), 10);
  EXPECT_LE(ours.maxError, theirs.maxError) << theirs.maxError << " covered " << ours.covered << " vs " << theirs.covered;
  for (const TinVertex& v : all.tin.vertices)
    EXPECT_TRUE(std::any_of(sampled.vertices.begin(), sampled.vertices.end(),
                            [&](const TinVertex& s) { return s.x == v.x && s.y == v.y && s.z == v.z; }));
}

TEST(GreedyInsertion, GeographicDemIsTriangulatedInMetres) {
  Dem dem = test::makeGeographicDem(240, 200, 8.0, 47.0);
  for (int r = 0; r < dem.height; ++r)
    for (int c = 0; c < dem.width; ++c) dem.z[std::size_t(r) * dem.width + c] = float(500 + 50 * std::sin(c * 0.07) * std::sin(r * 0.05));
  const InsertedTin out = insert(dem, 1);
  EXPECT_NE(out.tin.crsName.find("UTM zone 32N"), std::string::npos);
  const InsertGrid grid = makeInsertGrid(dem, CrsTransform::forDem(dem, "", "", kQuiet), nullptr);
  EXPECT_NEAR(grid.cellWidth, 63.4, 0.3);  // 92.77 m cos(46.92 deg)
  EXPECT_NEAR(grid.cellHeight, 92.7, 0.3);
  const std::array<double, 2> scale = delaunayScales(grid.cellWidth, grid.cellHeight);
  EXPECT_NEAR(scale[0] / scale[1], grid.cellWidth / grid.cellHeight, 1e-6);
  EXPECT_EQ(test::delaunayViolations(groundGrid(out.tin, scale[0], scale[1])), 0u);
  EXPECT_LE(out.summary.measuredMaxError, 1.0 + 1e-9);
  EXPECT_EQ(out.summary.uncoveredCells, 0u);
  // Cells of 1/1200 degree at 47 N: about 63 m by 93 m; the TIN spans the DEM's extent.
  double minX = 1e30, maxX = -1e30;
  for (const TinVertex& v : out.tin.vertices) minX = std::min(minX, v.x), maxX = std::max(maxX, v.x);
  EXPECT_NEAR(maxX - minX, 239 * 63.4, 239 * 1.5);
}

TEST(GreedyInsertion, GridDelaunayTreatsCellsAsSquares) {
  Dem dem = test::makeGeographicDem(200, 160, 8.0, 47.0);
  for (int r = 0; r < dem.height; ++r)
    for (int c = 0; c < dem.width; ++c) dem.z[std::size_t(r) * dem.width + c] = float(500 + 50 * std::sin(c * 0.09) * std::sin(r * 0.06));
  InsertOptions o;
  o.maxError = 0.5;
  o.delaunayOnGrid = true;
  const InsertedTin grid = greedyInsertionTin(dem, o, kQuiet);
  EXPECT_EQ(test::delaunayViolations(groundGrid(grid.tin, 1, 1)), 0u);
  EXPECT_LE(bruteForce(dem, grid.tin).maxError, 0.5 + kRounding);
  o.delaunayOnGrid = false;
  const InsertedTin ground = greedyInsertionTin(dem, o, kQuiet);
  EXPECT_NE(grid.tin.triangles, ground.tin.triangles);  // cells of 63 x 93 m: other triangles
  EXPECT_GT(test::delaunayViolations(groundGrid(grid.tin, 63.4, 92.7)), 0u);
}

TEST(GreedyInsertion, DelaunayScalesAreSmallWholeNumbers) {
  EXPECT_EQ(delaunayScales(88.814, 88.81399999), (std::array<double, 2>{1, 1}));  // square up to rounding
  EXPECT_EQ(delaunayScales(30, 60), (std::array<double, 2>{1, 2}));
  const std::array<double, 2> s = delaunayScales(63.4562563, 92.6119);
  EXPECT_NEAR(s[0] / s[1], 63.4562563 / 92.6119, 1e-6);
  EXPECT_LE(s[1], 4096);
  EXPECT_EQ(s[0], std::round(s[0]));
}

TEST(GreedyInsertion, BadOptionsNameTheParameter) {
  const Dem dem = hills(20, 20);
  InsertOptions o;
  o.maxError = -1;
  EXPECT_THROW(
      try { greedyInsertionTin(dem, o, kQuiet); } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("max_error"), std::string::npos);
        throw;
      },
      Error);
  o.maxError = 1, o.maxVertices = 2;
  EXPECT_THROW(greedyInsertionTin(dem, o, kQuiet), Error);
  EXPECT_THROW(parseCandidates("all"), Error);
  const Dem empty = test::makeDem(10, 10, 10, [](int, int) { return NAN; });
  EXPECT_THROW(insert(empty, 1), Error);
  const Dem line = test::makeDem(10, 10, 10, [](int r, int) { return r == 4 ? 1.f : NAN; });
  EXPECT_THROW(insert(line, 1), Error);
}

TEST(InsertJob, WritesTheTinWithInsertionOrderAndLeavesNothingWhenCancelled) {
  const std::string dir = test::tempDir();
  const std::string out = dir + "/insert.gpkg";
  InsertOptions o;
  o.maxError = 2;
  const InsertSummary s = runInsertJob(test::smallSyntheticDemFile(), out, o, false, Feedback{});
  GDALAllRegister();
  GDALDatasetUniquePtr ds(GDALDataset::Open(out.c_str(), GDAL_OF_VECTOR));
  ASSERT_TRUE(ds);
  OGRLayer* vertices = ds->GetLayerByName("vertices");
  ASSERT_NE(vertices, nullptr);
  EXPECT_EQ(vertices->GetFeatureCount(), GIntBig(s.vertices));
  EXPECT_GE(vertices->GetLayerDefn()->GetFieldIndex("insertion"), 0);
  EXPECT_GE(vertices->GetLayerDefn()->GetFieldIndex("error_before"), 0);
  EXPECT_EQ(ds->GetLayerByName("triangles")->GetFeatureCount(), GIntBig(s.triangles));
  EXPECT_STREQ(ds->GetMetadataItem("TINLOD_METHOD"), "insert");
  // The measured figures are written as the file is finished (the check runs beside the
  // writing), among the other items: exactly the summary's.
  ASSERT_NE(ds->GetMetadataItem("TINLOD_RMSE"), nullptr);
  ASSERT_NE(ds->GetMetadataItem("TINLOD_MEASURED_MAX_ERROR"), nullptr);
  EXPECT_NEAR(std::stod(ds->GetMetadataItem("TINLOD_RMSE")), s.rmse, 1e-5 * s.rmse);
  EXPECT_NEAR(std::stod(ds->GetMetadataItem("TINLOD_MEASURED_MAX_ERROR")), s.measuredMaxError, 1e-5 * s.measuredMaxError);
  EXPECT_STREQ(ds->GetMetadataItem("TINLOD_UNCOVERED_CELLS"), std::to_string(s.uncoveredCells).c_str());
  EXPECT_STREQ(ds->GetMetadataItem("TINLOD_CANDIDATES"), "cells");
  EXPECT_GT(s.measuredCells, 0u);
  EXPECT_LE(s.measuredMaxError, 2.0);
  ds.reset();

  const std::string cancelled = dir + "/cancelled.gpkg";
  Feedback stop;
  stop.progress = [](double f, const std::string&) { return f < 0.3; };
  EXPECT_THROW(runInsertJob(test::smallSyntheticDemFile(), cancelled, o, false, stop), Cancelled);
  EXPECT_FALSE(fs::exists(cancelled));
  // Cancelled as the file starts, with the independent check running beside it: on the
  // default DEM (1.2 M cells) the check is still reading the DEM and the TIN then, which
  // must outlive it (under ASan a use after free showed here).
  const std::string big = dir + "/default_dem.tif";
  writeDemGeoTiff(makeSyntheticDem(SyntheticDemOptions()), big);
  bool writing = false;
  Feedback late;
  late.progress = [&writing](double f, const std::string&) {
    writing = writing || f >= 0.86;
    return !writing;
  };
  o.maxError = 20;
  EXPECT_THROW(runInsertJob(big, cancelled, o, false, late), Cancelled);
  EXPECT_TRUE(writing);
  EXPECT_FALSE(fs::exists(cancelled));
  EXPECT_THROW(runInsertJob(test::smallSyntheticDemFile(), out, o, false, Feedback{}), Error);  // exists
  // Between the insertion and the file, the triangles are collected and cut free of the
  // holes: over a second for alps_2x2's million triangles, where a stop went unheard.
  for (const std::string phase : {"Collecting the triangles", "Cutting out nodata"}) {
    bool asked = false;
    Feedback there;
    there.progress = [&asked, phase](double, const std::string& now) {
      asked = asked || now == phase;
      return !asked;
    };
    EXPECT_THROW(runInsertJob(big, cancelled, o, false, there), Cancelled) << phase;
    EXPECT_TRUE(asked) << phase;
    EXPECT_FALSE(fs::exists(cancelled)) << phase;
  }
}

// Every feature of a layer, fid order: its fields as text and its geometry's WKB.
std::vector<std::string> featuresOf(const std::string& path, const char* layerName) {
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR));
  EXPECT_TRUE(ds);
  std::vector<std::string> out;
  if (!ds) return out;
  OGRLayer* layer = ds->GetLayerByName(layerName);
  EXPECT_NE(layer, nullptr);
  if (!layer) return out;
  for (auto& f : *layer) {
    std::string row = std::to_string(f->GetFID());
    for (int i = 0; i < f->GetFieldCount(); ++i) row += std::string("|") + (f->IsFieldNull(i) ? "null" : f->GetFieldAsString(i));
    if (const OGRGeometry* g = f->GetGeometryRef()) {
      std::string wkb(std::size_t(g->WkbSize()), '\0');
      g->exportToWkb(wkbNDR, reinterpret_cast<unsigned char*>(wkb.data()), wkbVariantIso);
      row += "|" + wkb;
    }
    out.push_back(row);
  }
  return out;
}

// Writes at `after` the file of `dem`'s insertion the way a TIN is written once it is
// made, and expects the job's file `during` to hold the same features, field for field.
void expectTheFileWrittenAfterTheInsertion(const Dem& dem, const InsertOptions& o, const std::string& during,
                                           const std::string& after, const std::string& label) {
  const InsertedTin t = greedyInsertionTin(dem, o, kQuiet);
  std::vector<ExtraField> extra{{"insertion", {}, true}, {"error_before", {}, false}};
  extra[0].values.assign(t.insertion.begin(), t.insertion.end());
  extra[1].values = t.errorBefore;
  writeTinGpkg(t.tin, after, GpkgWriteOptions{}, kQuiet, extra);
  for (const char* layer : {"vertices", "triangles"}) {
    const std::vector<std::string> a = featuresOf(during, layer), b = featuresOf(after, layer);
    ASSERT_EQ(a.size(), b.size()) << label << " " << layer;
    for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << label << " " << layer << " feature " << i + 1;
  }
}

// Without nodata, with every cell a candidate, the job writes the vertex rows on the other
// core while the insertion runs: the file is the one written after it, feature for
// feature, metadata included; a cancel during the insertion leaves nothing.
TEST(InsertJob, ADemOfNoPossibleTriangleFailsAsSampleDoesAndWritesNothing) {
  // A checkerboard of nodata: every valid cell is alone. insert wrote 0 triangles and
  // "Maximum error 0 m", exit 0.
  const std::string dir = test::tempDir();
  const Dem dem = test::makeDem(40, 40, 10, [](int r, int c) { return (r + c) % 2 ? std::nanf("") : float(100 + r + c); });
  writeDemGeoTiff(dem, dir + "/checker.tif");
  for (const bool samples : {false, true}) {
    InsertOptions o;
    if (samples) o.candidates = InsertCandidates::Samples;
    const std::string error = test::errorOf([&] { runInsertJob(dir + "/checker.tif", dir + "/tin.gpkg", o, false, Feedback{}); });
    EXPECT_NE(error.find("'" + dir + "/checker.tif' gives no triangle: its valid cells are isolated or in a line"), std::string::npos)
        << error;
    EXPECT_FALSE(fs::exists(dir + "/tin.gpkg"));
  }
}

TEST(InsertJob, TrianglesThatTurnOverInTheTinsCrsAreRefused) {
  // The whole world in Mollweide, whose poles are points: the TIN, triangulated on the ground
  // about the grid, overlapped itself in the CRS (148 triangles turned over).
  const std::string cap = test::polarDemFile("world.tif", -180, 360, 180, 1.0), out = test::tempDir() + "/world.gpkg";
  InsertOptions o;
  o.maxError = 30;
  o.sample.targetSrs = "ESRI:54009";
  const std::string error = test::errorOf([&] { runInsertJob(cap, out, o, false, Feedback{}); });
  EXPECT_NE(error.find(" of its triangles over against the DEM's grid"), std::string::npos) << error;
  EXPECT_FALSE(fs::exists(out));
}

TEST(InsertJob, VertexRowsWrittenDuringTheInsertionAreThoseWrittenAfterIt) {
  const std::string dir = test::tempDir();
  Dem dem = test::makeGeographicDem(300, 220, 7.0, 47.0);  // transformed to UTM: PROJ on both paths
  const Dem shape = hills(300, 220);
  dem.z = shape.z;
  const std::string demPath = dir + "/hills.tif";
  writeDemGeoTiff(dem, demPath);
  InsertOptions o;
  o.maxError = 0.5;
  const std::string during = dir + "/during.gpkg", after = dir + "/after.gpkg";
  const InsertSummary s = runInsertJob(demPath, during, o, false, Feedback{});
  EXPECT_GT(s.vertices, 2000u);

  expectTheFileWrittenAfterTheInsertion(readDem(demPath, 1, kQuiet), o, during, after, "hills");
  if (HasFatalFailure()) return;
  EXPECT_EQ(featuresOf(during, "vertices").size(), s.vertices);
  GDALDatasetUniquePtr ds(GDALDataset::Open(during.c_str(), GDAL_OF_VECTOR));
  ASSERT_TRUE(ds);
  OGRLayer* vertices = ds->GetLayerByName("vertices");
  OGREnvelope extent;
  ASSERT_EQ(vertices->GetExtent(&extent, false), OGRERR_NONE);  // from gpkg_contents, as QGIS reads it
  GDALDatasetUniquePtr ref(GDALDataset::Open(after.c_str(), GDAL_OF_VECTOR));
  OGREnvelope refExtent;
  ASSERT_EQ(ref->GetLayerByName("vertices")->GetExtent(&refExtent, false), OGRERR_NONE);
  EXPECT_EQ(extent.MinX, refExtent.MinX);
  EXPECT_EQ(extent.MaxY, refExtent.MaxY);
  EXPECT_EQ(vertices->GetFeatureCount(false), GIntBig(s.vertices));
  ASSERT_NE(ds->GetMetadataItem("TINLOD_MAX_ERROR"), nullptr);
  EXPECT_LE(std::stod(ds->GetMetadataItem("TINLOD_MAX_ERROR")), 0.5);
  EXPECT_STREQ(ds->GetMetadataItem("TINLOD_CRS"), "WGS 84 / UTM zone 32N (EPSG:32632)");
  EXPECT_STREQ(ds->GetMetadataItem("TINLOD_UNCOVERED_CELLS"), "0");
  ds.reset();

  const std::string cancelled = dir + "/cancelled.gpkg";
  Feedback stop;
  stop.progress = [](double f, const std::string& phase) { return !(phase == "Inserting points" && f > 0.4); };
  EXPECT_THROW(runInsertJob(demPath, cancelled, o, false, stop), Cancelled);
  EXPECT_FALSE(fs::exists(cancelled));
  std::size_t left = 0;
  for (const auto& entry : fs::directory_iterator(dir)) left += entry.path().filename() != "hills.tif" &&
                                                               entry.path().filename() != "during.gpkg" &&
                                                               entry.path().filename() != "after.gpkg";
  EXPECT_EQ(left, 0u);
}

// On real DEMs without nodata (LiDAR in UTM, SRTM in longitude/latitude), the job's file,
// its vertex rows written during the insertion, is the one written after it.
TEST(GreedyInsertionRealDems, VertexRowsWrittenDuringTheInsertionAreThoseWrittenAfterIt) {
  const std::string data = test::dataDir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent: real-DEM tests skipped";
  const std::string dir = test::tempDir();
  for (const auto& [name, tol] : {std::pair{"gabilan_mesa_lidar1m.tif", 0.5}, std::pair{"dead_sea_N31E035.tif", 20.0}}) {
    const std::string demPath = data + "/" + name;
    const Dem dem = readDem(demPath, 1, kQuiet);
    ASSERT_EQ(dem.validCount(), dem.z.size()) << name << " has nodata: the rows would not be written ahead";
    InsertOptions o;
    o.maxError = tol;
    const std::string during = dir + "/during_" + name + ".gpkg", after = dir + "/after_" + name + ".gpkg";
    runInsertJob(demPath, during, o, false, Feedback{});
    expectTheFileWrittenAfterTheInsertion(dem, o, during, after, name);
    if (HasFatalFailure()) return;
  }
}

TEST(GreedyInsertionRealDems, ToleranceHoldsOnRealDems) {
  const std::string data = test::dataDir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent: real-DEM tests skipped";
  for (const char* name : {"dead_sea_N31E035.tif", "patagonia_coast_S46W066.tif", "big_tujunga_30m.tif"}) {
    const Dem dem = readDem(data + "/" + name, 1, kQuiet);
    for (double tol : {5.0, 20.0}) {
      const InsertedTin out = insert(dem, tol);
      const BruteForce b = bruteForce(dem, out.tin);
      EXPECT_LE(b.maxError, tol + kRounding) << name;
      EXPECT_EQ(b.uncovered, out.summary.uncoveredCells) << name;
      EXPECT_EQ(test::trianglesOverNodata(dem, out.tin), 0u) << name;
      // Delaunay on the grid, whose cells are in the ratio of their ground sizes (1:1 for
      // square cells; near 2:3 for dead_sea's 1/1200 degree at 31 N).
      const InsertGrid grid = makeInsertGrid(dem, CrsTransform::forDem(dem, "", "", kQuiet), nullptr);
      const std::array<double, 2> scale = delaunayScales(grid.cellWidth, grid.cellHeight);
      EXPECT_EQ(test::delaunayViolations(groundGrid(out.tin, scale[0], scale[1])), 0u) << name << " at " << tol;
    }
  }
}

}  // namespace
}  // namespace tinlod
