// SPDX-License-Identifier: GPL-3.0-or-later
// The delete simplification's invariants at every level, for every measure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <tuple>

#include "mesh_checks.h"
#include "test_support.h"
#include "tinlod/dem_reader.h"
#include "tinlod/error.h"
#include "tinlod/hierarchy_builder.h"
#include "tinlod/sample_job.h"
#include "tinlod/synthetic_dem.h"

namespace tinlod {
namespace {

const ProgressRange kQuiet(Feedback{}, 0, 1);

using EdgeSet = std::multiset<std::pair<VertexId, VertexId>>;

// Directed edges of a set of triangles that no other triangle of the set shares.
EdgeSet outline(const Hierarchy& h, const std::uint32_t* begin, const std::uint32_t* end) {
  std::set<std::pair<VertexId, VertexId>> directed;
  for (const std::uint32_t* t = begin; t != end; ++t)
    for (int k = 0; k < 3; ++k) directed.insert({h.triangles[*t].v[k], h.triangles[*t].v[(k + 1) % 3]});
  EdgeSet out;
  for (const auto& [a, b] : directed)
    if (!directed.count({b, a})) out.insert({a, b});
  return out;
}

// Vertices of a level on its outline.
std::size_t outlineVertexCount(const Hierarchy& h, std::int32_t level) {
  const std::vector<std::uint32_t> tris = h.levelTriangles(level);
  std::set<VertexId> on;
  for (const auto& [a, b] : outline(h, tris.data(), tris.data() + tris.size())) on.insert(a), on.insert(b);
  return on.size();
}

// Each valid cell centre's distance to a level, its vertices at row + drow, col + dcol.
std::vector<double> cellDistances(const Dem& dem, const Hierarchy& h, std::int32_t level) {
  return test::cellDistances(dem, h, level, [](const TinVertex& v) {
    return std::array<double, 2>{v.col + double(v.dcol), v.row + double(v.drow)};
  });
}

// The level's recorded figures against the brute force; and, with -max_error E, every
// cell within max(E, level 0's own distance there).
void expectCellFigures(const Dem& dem, const Hierarchy& h) {
  const std::vector<double> zero = cellDistances(dem, h, 0);
  for (std::int32_t L = 0; L <= h.coarsest(); ++L) {
    SCOPED_TRACE("level " + std::to_string(L));
    const std::vector<double> d = L == 0 ? zero : cellDistances(dem, h, L);
    double worst = 0, sum = 0;
    std::int64_t cells = 0, beyond = 0;
    for (std::size_t i = 0; i < d.size(); ++i) {
      if (std::isnan(d[i])) continue;
      worst = std::max(worst, d[i]), sum += d[i] * d[i], ++cells;
      // A cell level 0 does not cover (ground a straightened outline took in) is bound by E.
      const double allowed = std::isnan(zero[i]) ? h.options.maxError : std::max(h.options.maxError, zero[i]);
      if (std::isfinite(h.options.maxError) && d[i] > allowed + 1e-6) ++beyond;
    }
    // Every covered cell counted; a raster corner's cell (its own vertex) may count twice.
    EXPECT_GE(h.levels[L].cells, cells);
    EXPECT_LE(h.levels[L].cells, cells + 4);
    EXPECT_NEAR(h.levels[L].maxError, worst, 1e-6);
    EXPECT_NEAR(h.levels[L].rmse, std::sqrt(sum / std::max<std::int64_t>(cells, 1)), 1e-6 * (1 + h.levels[L].rmse));
    EXPECT_EQ(beyond, 0) << "cells further than max(-max_error, level 0's distance)";
  }
}

// The outline of a level: its boundary edges.
std::vector<std::pair<VertexId, VertexId>> outlineEdges(const Hierarchy& h, std::int32_t level) {
  const std::vector<std::uint32_t> tris = h.levelTriangles(level);
  const EdgeSet edges = outline(h, tris.data(), tris.data() + tris.size());
  return {edges.begin(), edges.end()};
}

double segmentDistance(const TinVertex& p, const TinVertex& a, const TinVertex& b) {
  const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
  const double t = len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(p.x - a.x - t * dx, p.y - a.y - t * dy);
}

// Every level-0 outline vertex a level no longer has lies within `tolerance(level)` of
// that level's outline.
template <class Tolerance>
void expectOutlineWithin(const Hierarchy& h, Tolerance tolerance) {
  const auto level0 = outlineEdges(h, 0);
  std::set<VertexId> outline0;
  for (const auto& [a, b] : level0) outline0.insert(a), outline0.insert(b);
  for (std::int32_t L = 1; L <= h.coarsest(); ++L) {
    const auto edges = outlineEdges(h, L);
    double worst = 0;
    for (VertexId v : outline0) {
      if (h.vertexLevel[v] >= L) continue;
      double nearest = INFINITY;
      for (const auto& [a, b] : edges) nearest = std::min(nearest, segmentDistance(h.base.vertices[v], h.base.vertices[a], h.base.vertices[b]));
      worst = std::max(worst, nearest);
    }
    EXPECT_LE(worst, tolerance(L) + 1e-9) << "level " << L;
  }
}

std::size_t nodataCovered(const Dem& dem, const Hierarchy& h, std::int32_t level);

void expectValidHierarchy(const Dem& dem, const Hierarchy& h) {
  ASSERT_GE(h.levels.size(), 2u);
  const Tin level0 = h.levelTin(0);
  const double area0 = totalArea(level0);
  const test::Topology top0 = test::analyseTopology(level0);
  std::size_t previous = level0.vertices.size();
  for (std::int32_t L = 0; L <= h.coarsest(); ++L) {
    SCOPED_TRACE("level " + std::to_string(L));
    const Tin tin = h.levelTin(L);
    EXPECT_EQ(tin.vertices.size(), h.levels[L].vertices);
    EXPECT_EQ(tin.triangles.size(), h.levels[L].triangles);
    EXPECT_EQ(test::localDelaunayViolations(tin), 0u);
    if (h.options.keepOutline) EXPECT_EQ(test::delaunayViolations(tin), 0u);
    EXPECT_EQ(test::clockwiseTriangles(tin), 0u);
    EXPECT_EQ(test::trianglesOverNodata(dem, tin), 0u);
    // Area goes only with the ground the outline gives up: the cells no longer covered and
    // at most half a cell along each outline edge given up.
    const double cellArea = area0 / double(h.levels[0].cells);
    const double given = double(h.levels[0].cells - h.levels[L].cells) + 0.5 * double(h.levels[0].outlineVertices);
    if (h.options.keepOutline) EXPECT_NEAR(totalArea(tin), area0, 1e-9 * area0);
    // Where the outline bends into the TIN it may straighten out over ground with no nodata
    // centre: less than a cell along the outline.
    EXPECT_LE(totalArea(tin), area0 + std::sqrt(cellArea) * top0.perimeter);
    EXPECT_EQ(test::verticesInsideTriangles(tin), 0u);  // no triangle overlaps another
    EXPECT_GE(totalArea(tin), area0 - given * cellArea);
    EXPECT_EQ(h.levels[L].outlineVertices, outlineVertexCount(h, L));
    const test::Topology t = test::analyseTopology(tin);
    EXPECT_EQ(t.problem, "");
    EXPECT_EQ(t.unusedVertices, 0u);
    EXPECT_EQ(t.eulerCharacteristic(), t.expectedEuler());
    EXPECT_EQ(t.components, top0.components);  // holes stay holes, parts stay parts
    EXPECT_EQ(t.boundaryLoops, top0.boundaryLoops);
    if (L > 0) {
      EXPECT_LE(h.levels[L].deleted, static_cast<std::size_t>(std::floor(h.options.deletePct / 100 * previous)));
      EXPECT_EQ(h.levels[L].vertices + h.levels[L].deleted, previous);
    }
    previous = tin.vertices.size();
  }
  // The deleted set of each level was independent at the finer level.
  for (std::int32_t L = 1; L <= h.coarsest(); ++L) {
    std::set<VertexId> deleted;
    for (const Group& g : h.groups)
      if (g.level == L) deleted.insert(g.vertex);
    EXPECT_EQ(deleted.size(), h.levels[L].deleted) << "level " << L;
    EXPECT_GT(deleted.size(), 0u) << "level " << L;
    for (std::uint32_t t : h.levelTriangles(L - 1)) {
      const Triangle& v = h.triangles[t].v;
      for (int k = 0; k < 3; ++k)
        EXPECT_FALSE(deleted.count(v[k]) && deleted.count(v[(k + 1) % 3])) << "adjacent deleted vertices at level " << L;
    }
  }
  // Each group's accept and reject triangles, as the triangles name them.
  EXPECT_FALSE(h.linked() && !h.groups.empty()) << "buildHierarchy leaves the linking to its caller";
  Hierarchy linked = h;
  linkGroups(linked);
  for (const Group& g : linked.groups) {
    const auto [a0, a1] = linked.accept(g);
    const auto [r0, r1] = linked.reject(g);
    const bool open = std::size_t(a1 - a0) == std::size_t(r1 - r0) + 1;
    if (!open) {
      EXPECT_EQ(outline(h, a0, a1), outline(h, r0, r1)) << "group of vertex " << g.vertex;  // same star polygon
      EXPECT_EQ(std::size_t(a1 - a0), std::size_t(r1 - r0) + 2);
    } else {
      // An outline vertex: its two outline edges become one, the rest of the polygon stays.
      EdgeSet before = outline(h, a0, a1), after = outline(h, r0, r1);
      const VertexId first = h.rings[g.ringBegin], last = h.rings[g.ringEnd - 1];
      EXPECT_EQ(before.erase({g.vertex, first}), 1u);
      EXPECT_EQ(before.erase({last, g.vertex}), 1u);
      EXPECT_EQ(after.erase({last, first}), 1u);
      EXPECT_EQ(before, after) << "group of outline vertex " << g.vertex;
    }
    EXPECT_EQ(h.vertexLevel[g.vertex], g.level - 1);
    for (const std::uint32_t* t = a0; t != a1; ++t) EXPECT_EQ(h.triangles[*t].lastLevel, g.level - 1);
    for (const std::uint32_t* t = r0; t != r1; ++t) EXPECT_EQ(h.triangles[*t].firstLevel, g.level);
  }
  for (std::size_t v = 0; v < h.fixed.size(); ++v)
    if (h.fixed[v]) EXPECT_EQ(h.vertexLevel[v], h.coarsest()) << "fixed vertex " << v << " was deleted";
}

Hierarchy build(const Dem& dem, Measure measure, double deletePct = 20) {
  HierarchyOptions o;
  o.measure = measure;
  o.deletePct = deletePct;
  const Tin tin = sampleTin(dem, {}, kQuiet);
  return buildHierarchy(tin, dem, {}, o, kQuiet);
}

class EveryMeasure : public ::testing::TestWithParam<Measure> {};

TEST_P(EveryMeasure, DefaultDemHierarchyKeepsEveryInvariant) {
  const Dem dem = test::smallSyntheticDem();
  const Hierarchy h = build(dem, GetParam());
  expectValidHierarchy(dem, h);
  const std::size_t original = h.levels[0].vertices;
  // Stops at 5 % of the original vertices, unless the fixed outline alone is more.
  std::size_t fixedCount = std::count(h.fixed.begin(), h.fixed.end(), 1);
  EXPECT_LE(h.levels.back().vertices, std::max<std::size_t>(std::ceil(0.05 * original), fixedCount) + original / 50);
  std::printf("  %s: %zu levels, %zu -> %zu vertices, max error %.2f m\n", measureName(GetParam()).c_str(),
              h.levels.size(), original, h.levels.back().vertices, h.levels.back().maxError);
}

INSTANTIATE_TEST_SUITE_P(Measures, EveryMeasure,
                         ::testing::Values(Measure::Degree, Measure::Volume, Measure::Normal, Measure::Error),
                         [](const auto& info) { return measureName(info.param); });

TEST(Hierarchy, RecordedFiguresAreTheDemsAtEveryCellAndLevel) {
  SyntheticDemOptions small;
  small.width = 60, small.height = 50;
  const Dem dem = makeSyntheticDem(small);
  for (Measure m : {Measure::Error, Measure::Volume}) {
    SCOPED_TRACE(measureName(m));
    expectCellFigures(dem, build(dem, m));
  }
}

// A triangle keeps its error as a float: the nearest one not below the distance, so that a
// bound read from the stored errors still holds.
TEST(Hierarchy, StoredTriangleErrorIsTheSmallestFloatNotBelowTheDistance) {
  for (double d : {0.0, 0.1, 1.0 / 3.0, 2.5, 12345.678, 1e-40, 8848.86, 0.962344123456789}) {
    const float f = roundedUpError(d);
    EXPECT_GE(double(f), d) << d;
    EXPECT_LT(double(std::nextafter(f, -INFINITY)), d) << d;  // the next float down is below
  }
  EXPECT_EQ(roundedUpError(2.5), 2.5f);  // exact when the float holds it
}

TEST(Hierarchy, MaxErrorBoundsEveryLevel) {
  const Dem dem = test::smallSyntheticDem();
  HierarchyOptions o;
  o.measure = Measure::Error;
  o.maxError = 5;
  const Hierarchy h = buildHierarchy(sampleTin(dem, {}, kQuiet), dem, {}, o, kQuiet);
  expectCellFigures(dem, h);  // every cell within max(5, level 0's distance)
  EXPECT_GT(h.levels.back().vertices, std::size_t(0.05 * h.levels[0].vertices));  // stopped by the error
  EXPECT_NE(h.stopReason.find("-max_error 5"), std::string::npos) << h.stopReason;
  expectValidHierarchy(dem, h);
}

TEST(Hierarchy, PhasesAreReportedInTheOrderTheyHappenAndOnlyForLevelsMade) {
  const Dem dem = test::smallSyntheticDem();
  std::vector<std::string> phases;
  Feedback f;
  f.progress = [&](double, const std::string& phase) {
    if (phases.empty() || phases.back() != phase) phases.push_back(phase);
    return true;
  };
  const Hierarchy h = buildHierarchy(sampleTin(dem, {}, kQuiet), dem, {}, {}, ProgressRange(f, 0, 1));
  ASSERT_GE(h.coarsest(), 3);
  // Selecting level L, then Simplifying level L, for L = 1.. in turn; the selection that
  // finds the next level not worth making is the last phase, and no level is named that
  // was not made but that one.
  std::vector<std::string> levelPhases;
  for (const std::string& p : phases)
    if (p.rfind("Selecting level ", 0) == 0 || p.rfind("Simplifying level ", 0) == 0) levelPhases.push_back(p);
  std::vector<std::string> expected;
  for (std::int32_t L = 1; L <= h.coarsest(); ++L) {
    expected.push_back("Selecting level " + std::to_string(L));
    expected.push_back("Simplifying level " + std::to_string(L));
  }
  if (!h.stopReason.empty() && h.stopReason.find("-max_levels") == std::string::npos)
    expected.push_back("Selecting level " + std::to_string(h.coarsest() + 1));
  EXPECT_EQ(levelPhases, expected);
}

TEST(Hierarchy, DegreeMeasureDeletesOnlyLowDegreeVertices) {
  const Dem dem = test::smallSyntheticDem();
  const Hierarchy h = build(dem, Measure::Degree);
  for (const Group& g : h.groups) EXPECT_LE(g.ringEnd - g.ringBegin, 11u);
}

TEST(Hierarchy, FixedVerticesSurvive) {
  const Dem dem = test::smallSyntheticDem();
  const Tin tin = sampleTin(dem, {}, kQuiet);
  std::vector<std::uint8_t> fixed(tin.vertices.size(), 0);
  for (std::size_t v = 0; v < fixed.size(); v += 7) fixed[v] = 1;
  const Hierarchy h = buildHierarchy(tin, dem, fixed, {}, kQuiet);
  for (std::size_t v = 0; v < fixed.size(); v += 7) EXPECT_EQ(h.vertexLevel[v], h.coarsest());
  expectValidHierarchy(dem, h);
}

TEST(Hierarchy, ThresholdModeDeletesOnlyBelowTheThreshold) {
  const Dem dem = test::smallSyntheticDem();
  HierarchyOptions o;
  o.thresholdMode = true;
  o.threshold = 2000;  // cubic metres of volume change
  const Hierarchy h = buildHierarchy(sampleTin(dem, {}, kQuiet), dem, {}, o, kQuiet);
  ASSERT_FALSE(h.groups.empty());
  for (const Group& g : h.groups) EXPECT_LT(g.importance, 2000.0);
  expectValidHierarchy(dem, h);
}

// The threshold mode stops, as the percentage mode does, before a level that would delete
// under 1 % of its vertices (it went on with levels of 50, 29, 22, ... 2 vertices), and says why.
TEST(Hierarchy, ThresholdModeMakesNoLevelUnderOnePercentAndSaysWhyItStopped) {
  const Dem dem = test::smallSyntheticDem();
  HierarchyOptions o;
  o.thresholdMode = true;
  o.threshold = 1e5;
  const Hierarchy h = buildHierarchy(sampleTin(dem, {}, kQuiet), dem, {}, o, kQuiet);
  ASSERT_EQ(h.coarsest(), 12);
  EXPECT_EQ(h.levels.back().vertices, 1893u);
  for (std::int32_t L = 1; L <= h.coarsest(); ++L)
    EXPECT_GE(h.levels[L].deleted, h.levels[L - 1].vertices / 100) << "level " << L;
  EXPECT_EQ(h.stopReason, "the next level would delete only 13 vertices, under 1 % of them: the others' importance is not "
                          "below -threshold");
}

TEST(Hierarchy, FlatDemSimplifiesDeterministically) {
  const Dem dem = test::makeDem(90, 80, 10, [](int, int) { return 250.0f; });
  const Hierarchy a = build(dem, Measure::Volume), b = build(dem, Measure::Volume);
  ASSERT_EQ(a.groups.size(), b.groups.size());
  for (std::size_t i = 0; i < a.groups.size(); ++i) ASSERT_EQ(a.groups[i].vertex, b.groups[i].vertex);
  EXPECT_EQ(a.levels.back().maxError, 0.0);
  expectValidHierarchy(dem, a);
}

TEST(Hierarchy, BadOptionsNameTheOption) {
  HierarchyOptions o;
  o.deletePct = 0;
  EXPECT_THROW(o.validate(), Error);
  o = {};
  o.stopPct = 100;
  EXPECT_THROW(o.validate(), Error);
  o = {};
  o.maxError = 3;  // volume measure
  try {
    o.validate();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("-method error"), std::string::npos);
  }
  EXPECT_THROW(parseMeasure("curvature"), Error);
  o = {};
  o.maxLevels = kMaxLevel + 1;  // a triangle keeps its levels in 16 bits
  try {
    o.validate();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("max_levels"), std::string::npos) << e.what();
  }
  o.maxLevels = kMaxLevel;
  EXPECT_NO_THROW(o.validate());
}

// What the simplifier held only while it ran goes with it: level 0's neighbours were once
// "freed" by assigning an empty list, which keeps a vector's memory (45 MB on a 4096 x
// 4096 tile, to the end of the job).
TEST(Hierarchy, HoldsNoMemoryOfTheSimplifiersOwn) {
  const Dem dem = test::smallSyntheticDem();
  Tin tin = sampleTin(dem, SampleOptions(), ProgressRange(Feedback{}, 0, 1));
  ASSERT_FALSE(tin.neighbours.empty());
  const Hierarchy h = buildHierarchy(std::move(tin), dem, {}, HierarchyOptions(), ProgressRange(Feedback{}, 0, 1));
  EXPECT_EQ(h.base.neighbours.capacity(), 0u);
  EXPECT_EQ(h.base.triangles.size(), h.levels.front().triangles);
  EXPECT_EQ(h.base.triangles.capacity(), h.base.triangles.size());
}

// A survey (a tile's first pass, written as figures only) makes the very levels a build
// makes, without keeping their triangles, groups, links and rings, or measuring the levels
// above 0 against the DEM.
TEST(Hierarchy, SurveyMakesTheSameLevelsKeepingOnlyTheirCounts) {
  const Dem dem = test::smallSyntheticDem();
  const Tin tin = sampleTin(dem, {}, kQuiet);
  for (Measure m : {Measure::Volume, Measure::Error}) {
    SCOPED_TRACE(measureName(m));
    HierarchyOptions o;
    o.measure = m;
    const Hierarchy built = buildHierarchy(tin, dem, {}, o, kQuiet);
    o.survey = true;
    const Hierarchy surveyed = buildHierarchy(tin, dem, {}, o, kQuiet);
    ASSERT_EQ(surveyed.levels.size(), built.levels.size());
    ASSERT_GT(built.levels.size(), 3u);
    for (std::size_t k = 0; k < built.levels.size(); ++k) {
      const LevelStats &a = built.levels[k], &b = surveyed.levels[k];
      EXPECT_EQ(std::tie(a.vertices, a.triangles, a.deleted, a.outlineVertices),
                std::tie(b.vertices, b.triangles, b.deleted, b.outlineVertices))
          << "level " << k;
      // Only level 0 is measured against the DEM: no selection reads the others' errors.
      if (k == 0) EXPECT_EQ(std::tie(a.maxError, a.rmse, a.cells), std::tie(b.maxError, b.rmse, b.cells));
      else EXPECT_EQ(std::make_tuple(b.maxError, b.rmse, b.cells), std::make_tuple(0.0, 0.0, std::int64_t{0})) << "level " << k;
    }
    EXPECT_EQ(surveyed.vertexLevel, built.vertexLevel);
    ASSERT_EQ(surveyed.survey.size(), built.levels.size() - 1);
    for (const LevelSurvey& l : surveyed.survey) {
      EXPECT_EQ(l.picked, built.levels[l.level].deleted) << "level " << l.level;
      EXPECT_EQ(l.vertices, built.levels[l.level - 1].vertices) << "level " << l.level;
    }
    EXPECT_TRUE(built.survey.empty());
    EXPECT_TRUE(surveyed.triangles.empty() && surveyed.groups.empty() && surveyed.links.empty() &&
                surveyed.rings.empty() && surveyed.base.triangles.empty());
    EXPECT_EQ(surveyed.rings.capacity(), 0u);
  }
}

// A survey's level walks on past its picks through every candidate: its walk's picks by
// bin are what a threshold set anywhere takes in that state. A build with level 1's
// threshold at a bin beyond the delete percentage's picks deletes exactly the walk's picks
// up to it, more than a fifth of the vertices.
TEST(Hierarchy, SurveyWalkIsWhatAThresholdTakes) {
  const Dem dem = test::smallSyntheticDem();
  const Tin tin = sampleTin(dem, {}, kQuiet);
  HierarchyOptions o;
  o.survey = true;
  const Hierarchy surveyed = buildHierarchy(tin, dem, {}, o, kQuiet);
  ASSERT_FALSE(surveyed.survey.empty());
  const LevelSurvey& l = surveyed.survey.front();
  ASSERT_EQ(l.walkHistogram.size(), l.histogram.size());
  const int lastPicked = surveyBin(l.last);
  std::uint64_t walked = 0;
  int beyond = 0;  // the first bin where the walk has taken a quarter more than the picks
  for (int b = 0; b < kSurveyBins && !beyond; ++b) {
    if (b < lastPicked) EXPECT_EQ(l.walkHistogram[b], l.pickedHistogram[b]) << "bin " << b;
    EXPECT_LE(l.walkHistogram[b], l.histogram[b]) << "bin " << b;
    walked += l.walkHistogram[b];
    if (4 * walked >= 5 * l.picked) beyond = b;
  }
  ASSERT_GT(beyond, lastPicked);
  HierarchyOptions t;
  t.maxLevels = 1;
  t.levelThresholds = {surveyBinTop(beyond)};
  const Hierarchy built = buildHierarchy(tin, dem, {}, t, kQuiet);
  ASSERT_EQ(built.levels.size(), 2u);
  EXPECT_EQ(built.levels[1].deleted, walked);
  EXPECT_GT(5 * walked, l.vertices);
}

// With one threshold per level (a tile's second pass), the share of the threshold's bin is
// the share of its candidates that go: on a flat half, where every importance is 0 and
// independence blocks some candidates, exactly that share of them is deleted, not that
// share gone through (fewer, by what the neighbours block).
TEST(Hierarchy, LevelShareIsTheShareOfTiesDeleted) {
  const Dem dem = test::makeDem(90, 60, 10, [](int x, int y) { return x < 45 ? 0.f : float(40 * std::sin(0.3 * x) * std::cos(0.2 * y)); });
  const Tin tin = sampleTin(dem, {}, kQuiet);
  HierarchyOptions o;
  o.survey = true;
  o.maxLevels = 3;
  o.levelThresholds = {surveyBinTop(0), surveyBinTop(0), surveyBinTop(0)};
  o.levelShares = {0.3, 0.15, 0.1};
  const Hierarchy h = buildHierarchy(tin, dem, {}, o, kQuiet);
  ASSERT_EQ(h.survey.size(), 3u);
  for (const LevelSurvey& l : h.survey) {
    SCOPED_TRACE("level " + std::to_string(l.level));
    const std::uint64_t ties = l.histogram[0];
    ASSERT_GT(ties, 100u);
    EXPECT_EQ(std::accumulate(l.histogram.begin(), l.histogram.end(), std::uint64_t{0}), ties);  // all flat
    EXPECT_EQ(l.picked, static_cast<std::size_t>(std::floor(o.levelShares[l.level - 1] * double(ties))));
    EXPECT_GT(l.considered, l.picked);  // some were blocked: a share gone through would fall short
  }
}

TEST(Hierarchy, RealDemsEveryMeasure) {
  const std::string dir = test::dataDir();
  if (dir.empty()) GTEST_SKIP() << "../shared/data is absent (set TINLOD_TEST_DATA): real-DEM test skipped";
  for (const char* file : {"tntn_sf_valid_raster.tif", "dc_lidar2m_dtm.tif", "bavaria_dgm5_bottomup.tif"}) {
    const Dem dem = readDem(dir + "/" + file, 1, kQuiet);
    SampleOptions so;
    so.jitter = 0.1;
    const Tin tin = sampleTin(dem, so, kQuiet);
    for (Measure m : {Measure::Degree, Measure::Volume, Measure::Normal, Measure::Error}) {
      SCOPED_TRACE(std::string(file) + " " + measureName(m));
      HierarchyOptions o;
      o.measure = m;
      if (m == Measure::Error) o.maxError = 1;  // every cell within max(1 m, level 0's distance)
      const Hierarchy h = buildHierarchy(tin, dem, {}, o, kQuiet);
      expectValidHierarchy(dem, h);
      if (m == Measure::Error || m == Measure::Volume) expectCellFigures(dem, h);
      const double cell = std::fabs(dem.geotransform[1]);  // square cells, in the TIN's CRS
      expectOutlineWithin(h, [&](std::int32_t L) {
        return cell * std::sqrt(double(h.levels[0].vertices) / double(h.levels[L - 1].vertices)) * (1 + 1e-6);
      });
      for (std::int32_t L = 0; L <= h.coarsest(); L += 3) EXPECT_EQ(nodataCovered(dem, h, L), 0u) << "level " << L;
    }
  }
}

// The same TIN with its triangles listed in another order, each starting at another
// corner: the simplifier walks stars from their smallest vertex and breaks ties by id, so
// the same vertices go at the same levels with the same importances, and every level has
// the same triangles. The sampled TIN is linked from its triangulation's neighbours; the
// shuffled copy still carries them, no longer fitting, and is linked by the edge search.
TEST(Hierarchy, ResultDoesNotDependOnTheOrderOfTheTriangles) {
  const Dem dem = test::smallSyntheticDem();
  const Tin tin = sampleTin(dem, {}, kQuiet);
  ASSERT_EQ(tin.neighbours.size(), tin.triangles.size());
  Tin shuffled = tin;
  std::reverse(shuffled.triangles.begin(), shuffled.triangles.end());
  for (std::size_t t = 0; t < shuffled.triangles.size(); t += 2)
    std::rotate(shuffled.triangles[t].begin(), shuffled.triangles[t].begin() + 1, shuffled.triangles[t].end());
  for (Measure m : {Measure::Volume, Measure::Error}) {
    HierarchyOptions o;
    o.measure = m;
    const Hierarchy a = buildHierarchy(tin, dem, {}, o, kQuiet), b = buildHierarchy(shuffled, dem, {}, o, kQuiet);
    ASSERT_EQ(a.groups.size(), b.groups.size());
    for (std::size_t g = 0; g < a.groups.size(); ++g) {
      ASSERT_EQ(a.groups[g].vertex, b.groups[g].vertex);
      ASSERT_EQ(a.groups[g].level, b.groups[g].level);
      ASSERT_EQ(a.groups[g].importance, b.groups[g].importance);
      ASSERT_EQ(a.groups[g].error, b.groups[g].error);
    }
    for (std::int32_t level = 0; level <= a.coarsest(); ++level) {
      auto triangles = [&](const Hierarchy& h) {
        std::set<std::array<VertexId, 3>> out;
        for (std::uint32_t t : h.levelTriangles(level)) {
          Triangle v = h.triangles[t].v;
          std::rotate(v.begin(), std::min_element(v.begin(), v.end()), v.end());
          out.insert(v);
        }
        return out;
      };
      EXPECT_EQ(triangles(a), triangles(b)) << measureName(m) << " level " << level;
    }
  }
}

// Level 0 must be a Delaunay TIN with counter-clockwise triangles: a flipped diagonal,
// a clockwise triangle or two triangles on one side of an edge are refused.
TEST(Hierarchy, RefusesALevelZeroThatIsNotDelaunay) {
  const Dem dem = test::makeDem(2, 2, 1, [](int, int) { return 0.0f; });
  Tin quad;
  quad.vertices = {{0, 0, 0}, {10, 0, 0}, {10, 1, 0}, {0, 1, 0}};
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};  // cocircular: either diagonal is Delaunay
  EXPECT_NO_THROW(buildHierarchy(quad, dem, {}, {}, kQuiet));
  Tin bad;
  bad.vertices = {{0, 0, 0}, {10, 0, 0}, {5, 1, 0}, {5, -1, 0}};
  bad.triangles = {{0, 1, 2}, {1, 0, 3}};  // the long diagonal 0-1 of a thin rhombus
  try {
    buildHierarchy(bad, dem, {}, {}, kQuiet);
    ADD_FAILURE() << "a non-Delaunay diagonal was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not a Delaunay triangulation"), std::string::npos) << e.what();
  }
  Tin clockwise = quad;
  std::swap(clockwise.triangles[0][1], clockwise.triangles[0][2]);
  EXPECT_THROW(buildHierarchy(clockwise, dem, {}, {}, kQuiet), Error);
  Tin doubled = quad;
  doubled.triangles.push_back({0, 1, 2});
  EXPECT_THROW(buildHierarchy(doubled, dem, {}, {}, kQuiet), Error);
  Tin doubledInside = quad;  // the copy shares the inner diagonal, not only outline edges
  doubledInside.triangles.push_back({2, 3, 0});
  EXPECT_THROW(buildHierarchy(doubledInside, dem, {}, {}, kQuiet), Error);
}

// A vertex of degree 100 (above the small-star scratch) in the middle of a ring, deleted in
// threshold mode: its hole is filled with 98 Delaunay triangles over the same area.
TEST(Hierarchy, DeletesAVertexOfVeryHighDegree) {
  Tin fan;
  fan.vertices.push_back({0, 0, 5});
  const int n = 100;
  for (int i = 0; i < n; ++i)
    fan.vertices.push_back({1000 * std::cos(2 * M_PI * i / n), 1000 * std::sin(2 * M_PI * i / n), 0});
  for (int i = 0; i < n; ++i) fan.triangles.push_back({0, VertexId(1 + i), VertexId(1 + (i + 1) % n)});
  const Dem dem = test::demUnder(fan, 10);  // the centre lies on a cell centre
  HierarchyOptions o;
  o.thresholdMode = true;
  o.threshold = 1e300;
  o.maxLevels = 1;
  o.keepOutline = true;  // the centre, not its ring, is the vertex to delete
  const Hierarchy h = buildHierarchy(fan, dem, {}, o, kQuiet);
  ASSERT_EQ(h.coarsest(), 1);
  ASSERT_EQ(h.groups.size(), 1u);
  const Tin top = h.levelTin(1);
  EXPECT_EQ(top.triangles.size(), std::size_t(n - 2));
  EXPECT_EQ(test::delaunayViolations(top), 0u);
  EXPECT_NEAR(totalArea(top), totalArea(fan), 1e-9 * totalArea(fan));
  EXPECT_DOUBLE_EQ(h.groups[0].error, 5.0);  // the centre, over a flat ring
}

// With the error measure a vertex's importance is the error its deletion certifies, so
// -max_error bounds every group and every level.
TEST(Hierarchy, ErrorImportanceIsTheCertifiedErrorAndMaxErrorHolds) {
  HierarchyOptions o;
  o.measure = Measure::Error;
  o.maxError = 40;
  const Dem dem = test::smallSyntheticDem();
  const Hierarchy h = buildHierarchy(sampleTin(dem, {}, kQuiet), dem, {}, o, kQuiet);
  ASSERT_GE(h.coarsest(), 2);
  for (const Group& g : h.groups) ASSERT_EQ(g.importance, g.error) << "vertex " << g.vertex;
  expectCellFigures(dem, h);
}

TEST(Hierarchy, PatagoniaSeaSimplifiesDeterministically) {
  const std::string dir = test::dataDir();
  if (dir.empty()) GTEST_SKIP() << "../shared/data is absent (set TINLOD_TEST_DATA): real-DEM test skipped";
  const Dem dem = readDem(dir + "/patagonia_coast_S46W066.tif", 1, kQuiet);
  SampleOptions so;
  so.block = 9;  // 160 k vertices: the flat sea is what matters here
  const Tin tin = sampleTin(dem, so, kQuiet);
  const Hierarchy a = buildHierarchy(tin, dem, {}, {}, kQuiet), b = buildHierarchy(tin, dem, {}, {}, kQuiet);
  ASSERT_EQ(a.groups.size(), b.groups.size());
  for (std::size_t i = 0; i < a.groups.size(); i += 97) ASSERT_EQ(a.groups[i].vertex, b.groups[i].vertex);
  const Tin top = a.levelTin(a.coarsest());
  EXPECT_EQ(test::localDelaunayViolations(top), 0u);
  // A DEM in degrees: the TIN may reach past a raster edge's bent line of centres, never
  // by more than half a cell (about 30 m at 1").
  EXPECT_LE(totalArea(top), totalArea(tin) + 15 * test::analyseTopology(tin).perimeter);
}

// Nodata cell centres inside a level's triangles (closed, in the grid, vertices where the
// jitter put them), or centres off the raster: none at any level.
std::size_t nodataCovered(const Dem& dem, const Hierarchy& h, std::int32_t level) {
  std::size_t n = 0;
  for (std::uint32_t id : h.levelTriangles(level)) {
    const Triangle& t = h.triangles[id].v;
    double c[3], r[3];
    for (int k = 0; k < 3; ++k) {
      const TinVertex& v = h.base.vertices[t[k]];
      c[k] = v.col + double(v.dcol), r[k] = v.row + double(v.drow);
    }
    const double d = (c[1] - c[0]) * (r[2] - r[0]) - (c[2] - c[0]) * (r[1] - r[0]);
    for (int row = int(std::floor(std::min({r[0], r[1], r[2]}))); row <= int(std::ceil(std::max({r[0], r[1], r[2]}))); ++row)
      for (int col = int(std::floor(std::min({c[0], c[1], c[2]}))); col <= int(std::ceil(std::max({c[0], c[1], c[2]}))); ++col) {
        if (dem.valid(row, col)) continue;
        const double wb = ((col - c[0]) * (r[2] - r[0]) - (c[2] - c[0]) * (row - r[0])) / d;
        const double wc = ((c[1] - c[0]) * (row - r[0]) - (col - c[0]) * (r[1] - r[0])) / d;
        n += wb > 1e-9 && wc > 1e-9 && wb + wc < 1 - 1e-9;
      }
  }
  return n;
}

// A DEM with a lake, a void and nodata on its rim: the outline of the data and of its holes
// is simplified with the rest, never further than the tolerance (one cell at level 1,
// growing as the vertex spacing does), never over nodata, and it gives up few cells.
TEST(Hierarchy, OutlineIsSimplifiedWithinItsTolerance) {
  const Dem dem = test::smallSyntheticDem();
  const Tin tin = sampleTin(dem, {}, kQuiet);
  for (Measure m : {Measure::Volume, Measure::Error}) {
    SCOPED_TRACE(measureName(m));
    HierarchyOptions o;
    o.measure = m;
    const Hierarchy h = buildHierarchy(tin, dem, {}, o, kQuiet);
    expectValidHierarchy(dem, h);
    const double cell = 25;
    expectOutlineWithin(h, [&](std::int32_t L) {
      return cell * std::sqrt(double(h.levels[0].vertices) / double(h.levels[L - 1].vertices)) * (1 + 1e-6);
    });
    for (std::int32_t L = 0; L <= h.coarsest(); ++L) EXPECT_EQ(nodataCovered(dem, h, L), 0u) << "level " << L;
    const LevelStats& top = h.levels.back();
    EXPECT_LT(top.outlineVertices, h.levels[0].outlineVertices / 2) << "the outline was hardly simplified";
    EXPECT_LT(double(h.levels[0].cells - top.cells), 0.02 * double(h.levels[0].cells));
    std::printf("  %s: outline %zu -> %zu vertices (%.1f %% of the coarsest level), %lld cells given up\n",
                measureName(m).c_str(), h.levels[0].outlineVertices, top.outlineVertices,
                100.0 * top.outlineVertices / top.vertices, static_cast<long long>(h.levels[0].cells - top.cells));
  }
}

// -keep_outline: every outline vertex stays, so each level has level 0's outline and area.
TEST(Hierarchy, KeepOutlineKeepsEveryOutlineVertex) {
  const Dem dem = test::smallSyntheticDem();
  HierarchyOptions o;
  o.keepOutline = true;
  const Hierarchy h = buildHierarchy(sampleTin(dem, {}, kQuiet), dem, {}, o, kQuiet);
  expectValidHierarchy(dem, h);
  for (const LevelStats& l : h.levels) {
    EXPECT_EQ(l.outlineVertices, h.levels[0].outlineVertices);
    EXPECT_EQ(l.cells, h.levels[0].cells);
  }
}

// A rectangular projected DEM: its edge cells lie on the edge lines, so every level keeps
// the exact rectangle (same area, the four corners, every outline vertex on an edge line)
// while most of the edge's vertices go.
TEST(Hierarchy, RectangularProjectedDemKeepsItsExactRectangle) {
  const Dem dem = test::makeDem(120, 90, 10, [](int r, int c) { return float(100 + 20 * std::sin(r * 0.11) * std::cos(c * 0.07)); });
  const Tin tin = sampleTin(dem, {}, kQuiet);
  const double x0 = dem.centreX(0), x1 = dem.centreX(dem.width - 1), y0 = dem.centreY(dem.height - 1), y1 = dem.centreY(0);
  const Hierarchy h = buildHierarchy(tin, dem, {}, {}, kQuiet);
  expectValidHierarchy(dem, h);
  for (std::int32_t L = 0; L <= h.coarsest(); ++L) {
    SCOPED_TRACE("level " + std::to_string(L));
    const Tin level = h.levelTin(L);
    EXPECT_NEAR(totalArea(level), (x1 - x0) * (y1 - y0), 1e-9 * (x1 - x0) * (y1 - y0));
    for (const auto& [a, b] : outlineEdges(h, L))
      for (VertexId v : {a, b}) {
        const TinVertex& p = h.base.vertices[v];
        EXPECT_TRUE(p.x == x0 || p.x == x1 || p.y == y0 || p.y == y1) << "outline vertex off the rectangle";
      }
    EXPECT_EQ(h.levels[L].cells, std::int64_t(dem.width) * dem.height);
  }
  EXPECT_LE(h.levels.back().outlineVertices, h.levels.back().vertices / 4);
}

// A DEM in degrees: the raster's edges bend by a hair in UTM, and their vertices still go.
TEST(Hierarchy, GeographicDemOutlineIsSimplifiedToo) {
  Dem dem = test::makeGeographicDem(150, 120, 7.5, 46.5);
  for (int r = 0; r < dem.height; ++r)
    for (int c = 0; c < dem.width; ++c) dem.z[std::size_t(r) * dem.width + c] = float(800 + 50 * std::sin(r * 0.2) + 30 * std::cos(c * 0.13));
  const Hierarchy h = buildHierarchy(sampleTin(dem, {}, kQuiet), dem, {}, {}, kQuiet);
  expectValidHierarchy(dem, h);
  EXPECT_LE(h.levels.back().outlineVertices, h.levels.back().vertices / 4);
  EXPECT_EQ(h.levels.back().cells, h.levels[0].cells);  // an edge's cells stay covered in the grid
}

// A DEM in degrees riddled with voids (as SRTM's): hole edges bend into the data and out of
// it, so outline vertices go both ways; every level stays Delaunay constrained by its
// outline, covers no nodata centre and keeps every cell within the error bound.
TEST(Hierarchy, VoidRiddledGeographicDem) {
  Dem dem = test::makeGeographicDem(220, 180, 8.25, 46.75);
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> rowAt(0, dem.height - 1), colAt(0, dem.width - 1), size(1, 6);
  for (int r = 0; r < dem.height; ++r)
    for (int c = 0; c < dem.width; ++c)
      dem.z[std::size_t(r) * dem.width + c] = float(1200 + 300 * std::sin(r * 0.05) * std::cos(c * 0.04) + 40 * std::sin(r * 0.3 + c * 0.2));
  for (int hole = 0; hole < 60; ++hole) {
    const int r0 = rowAt(rng), c0 = colAt(rng), rr = size(rng), cc = size(rng);
    for (int r = r0; r < std::min(dem.height, r0 + rr); ++r)
      for (int c = c0; c < std::min(dem.width, c0 + cc); ++c)
        if ((r - r0) * (r - r0 + 1) + (c - c0) * (c - c0 + 1) <= rr * cc) dem.z[std::size_t(r) * dem.width + c] = NAN;
  }
  const Tin tin = sampleTin(dem, {}, kQuiet);
  for (Measure m : {Measure::Volume, Measure::Error}) {
    SCOPED_TRACE(measureName(m));
    HierarchyOptions o;
    o.measure = m;
    if (m == Measure::Error) o.maxError = 5;
    const Hierarchy h = buildHierarchy(tin, dem, {}, o, kQuiet);
    expectValidHierarchy(dem, h);
    expectCellFigures(dem, h);
    for (std::int32_t L = 0; L <= h.coarsest(); L += 2) EXPECT_EQ(nodataCovered(dem, h, L), 0u) << "level " << L;
    std::printf("  %s: %zu -> %zu vertices, outline %.1f %% of the coarsest level\n", measureName(m).c_str(),
                h.levels[0].vertices, h.levels.back().vertices, 100.0 * h.levels.back().outlineVertices / h.levels.back().vertices);
  }
}

}  // namespace
}  // namespace tinlod
