// SPDX-License-Identifier: GPL-3.0-or-later
// The delete simplification's invariants at every level, for every measure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

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
    EXPECT_EQ(test::delaunayViolations(tin), 0u);
    EXPECT_EQ(test::clockwiseTriangles(tin), 0u);
    EXPECT_EQ(test::trianglesOverNodata(dem, tin), 0u);
    EXPECT_NEAR(totalArea(tin), area0, 1e-9 * area0);
    const test::Topology t = test::analyseTopology(tin);
    EXPECT_EQ(t.problem, "");
    EXPECT_EQ(t.unusedVertices, 0u);
    EXPECT_EQ(t.eulerCharacteristic(), t.expectedEuler());
    EXPECT_EQ(t.components, top0.components);  // holes stay holes, parts stay parts
    EXPECT_EQ(t.boundaryLoops, top0.boundaryLoops);
    if (L > 0) {
      EXPECT_LE(h.levels[L].deleted, static_cast<std::size_t>(std::floor(h.options.deletePct / 100 * previous)));
      EXPECT_EQ(h.levels[L].vertices + h.levels[L].deleted, previous);
      EXPECT_GE(h.levels[L].maxError, h.levels[L - 1].maxError * 0);  // recorded
    }
    previous = tin.vertices.size();
  }
  // The deleted set of each level was independent at the finer level.
  for (std::int32_t L = 1; L <= h.coarsest(); ++L) {
    std::set<VertexId> deleted;
    for (const Group& g : h.groups)
      if (g.level == L) deleted.insert(g.vertex);
    for (std::uint32_t t : h.levelTriangles(L - 1)) {
      const Triangle& v = h.triangles[t].v;
      for (int k = 0; k < 3; ++k)
        EXPECT_FALSE(deleted.count(v[k]) && deleted.count(v[(k + 1) % 3])) << "adjacent deleted vertices at level " << L;
    }
  }
  for (const Group& g : h.groups) {
    const auto [a0, a1] = h.accept(g);
    const auto [r0, r1] = h.reject(g);
    EXPECT_EQ(outline(h, a0, a1), outline(h, r0, r1)) << "group of vertex " << g.vertex;  // same star polygon
    EXPECT_EQ(std::size_t(a1 - a0), std::size_t(r1 - r0) + 2);
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
  return buildHierarchy(tin, {}, o, kQuiet);
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

// Brute force: the vertical distance from every level-0 sample to each level's surface.
double bruteForceError(const Hierarchy& h, std::int32_t level) {
  const Tin tin = h.levelTin(level);
  double worst = 0;
  for (const TinVertex& s : h.base.vertices) {
    for (const Triangle& t : tin.triangles) {
      const TinVertex &a = tin.vertices[t[0]], &b = tin.vertices[t[1]], &c = tin.vertices[t[2]];
      const double d = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
      const double wb = ((s.x - a.x) * (c.y - a.y) - (c.x - a.x) * (s.y - a.y)) / d;
      const double wc = ((b.x - a.x) * (s.y - a.y) - (s.x - a.x) * (b.y - a.y)) / d;
      if (wb < -1e-12 || wc < -1e-12 || wb + wc > 1 + 1e-12) continue;
      worst = std::max(worst, std::fabs(s.z - (a.z + wb * (b.z - a.z) + wc * (c.z - a.z))));
      break;
    }
  }
  return worst;
}

TEST(Hierarchy, RecordedErrorIsTheTrueMaximumAtEveryLevel) {
  SyntheticDemOptions small;
  small.width = 60, small.height = 50;
  const Dem dem = makeSyntheticDem(small);
  for (Measure m : {Measure::Error, Measure::Volume}) {
    const Hierarchy h = build(dem, m);
    for (std::int32_t L = 0; L <= h.coarsest(); ++L)
      EXPECT_NEAR(h.levels[L].maxError, bruteForceError(h, L), 1e-6) << measureName(m) << " level " << L;
  }
}

TEST(Hierarchy, MaxErrorBoundsEveryLevel) {
  const Dem dem = test::smallSyntheticDem();
  HierarchyOptions o;
  o.measure = Measure::Error;
  o.maxError = 5;
  const Hierarchy h = buildHierarchy(sampleTin(dem, {}, kQuiet), {}, o, kQuiet);
  for (const LevelStats& l : h.levels) EXPECT_LE(l.maxError, 5.0);
  EXPECT_GT(h.levels.back().vertices, std::size_t(0.05 * h.levels[0].vertices));  // stopped by the error
  expectValidHierarchy(dem, h);
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
  const Hierarchy h = buildHierarchy(tin, fixed, {}, kQuiet);
  for (std::size_t v = 0; v < fixed.size(); v += 7) EXPECT_EQ(h.vertexLevel[v], h.coarsest());
  expectValidHierarchy(dem, h);
}

TEST(Hierarchy, ThresholdModeDeletesOnlyBelowTheThreshold) {
  const Dem dem = test::smallSyntheticDem();
  HierarchyOptions o;
  o.thresholdMode = true;
  o.threshold = 2000;  // cubic metres of volume change
  const Hierarchy h = buildHierarchy(sampleTin(dem, {}, kQuiet), {}, o, kQuiet);
  ASSERT_FALSE(h.groups.empty());
  for (const Group& g : h.groups) EXPECT_LT(g.importance, 2000.0);
  expectValidHierarchy(dem, h);
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
      expectValidHierarchy(dem, buildHierarchy(tin, {}, o, kQuiet));
    }
  }
}

// The same TIN with its triangles listed in another order, each starting at another
// corner: the simplifier walks stars from their smallest vertex and breaks ties by id, so
// the same vertices go at the same levels with the same importances, and every level has
// the same triangles. The sampled TIN is linked from its triangulation's neighbours; the
// shuffled copy still carries them, no longer fitting, and is linked by the edge search.
TEST(Hierarchy, ResultDoesNotDependOnTheOrderOfTheTriangles) {
  const Tin tin = sampleTin(test::smallSyntheticDem(), {}, kQuiet);
  ASSERT_EQ(tin.neighbours.size(), tin.triangles.size());
  Tin shuffled = tin;
  std::reverse(shuffled.triangles.begin(), shuffled.triangles.end());
  for (std::size_t t = 0; t < shuffled.triangles.size(); t += 2)
    std::rotate(shuffled.triangles[t].begin(), shuffled.triangles[t].begin() + 1, shuffled.triangles[t].end());
  for (Measure m : {Measure::Volume, Measure::Error}) {
    HierarchyOptions o;
    o.measure = m;
    const Hierarchy a = buildHierarchy(tin, {}, o, kQuiet), b = buildHierarchy(shuffled, {}, o, kQuiet);
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
  Tin quad;
  quad.vertices = {{0, 0, 0}, {10, 0, 0}, {10, 1, 0}, {0, 1, 0}};
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};  // cocircular: either diagonal is Delaunay
  EXPECT_NO_THROW(buildHierarchy(quad, {}, {}, kQuiet));
  Tin bad;
  bad.vertices = {{0, 0, 0}, {10, 0, 0}, {5, 1, 0}, {5, -1, 0}};
  bad.triangles = {{0, 1, 2}, {1, 0, 3}};  // the long diagonal 0-1 of a thin rhombus
  try {
    buildHierarchy(bad, {}, {}, kQuiet);
    ADD_FAILURE() << "a non-Delaunay diagonal was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not a Delaunay triangulation"), std::string::npos) << e.what();
  }
  Tin clockwise = quad;
  std::swap(clockwise.triangles[0][1], clockwise.triangles[0][2]);
  EXPECT_THROW(buildHierarchy(clockwise, {}, {}, kQuiet), Error);
  Tin doubled = quad;
  doubled.triangles.push_back({0, 1, 2});
  EXPECT_THROW(buildHierarchy(doubled, {}, {}, kQuiet), Error);
  Tin doubledInside = quad;  // the copy shares the inner diagonal, not only outline edges
  doubledInside.triangles.push_back({2, 3, 0});
  EXPECT_THROW(buildHierarchy(doubledInside, {}, {}, kQuiet), Error);
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
  HierarchyOptions o;
  o.thresholdMode = true;
  o.threshold = 1e300;
  o.maxLevels = 1;
  const Hierarchy h = buildHierarchy(fan, {}, o, kQuiet);
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
  const Hierarchy h = buildHierarchy(sampleTin(test::smallSyntheticDem(), {}, kQuiet), {}, o, kQuiet);
  ASSERT_GE(h.coarsest(), 2);
  for (const Group& g : h.groups) {
    ASSERT_EQ(g.importance, g.error) << "vertex " << g.vertex;
    ASSERT_LE(g.error, 40);
  }
  for (const LevelStats& l : h.levels) EXPECT_LE(l.maxError, 40);
}

TEST(Hierarchy, PatagoniaSeaSimplifiesDeterministically) {
  const std::string dir = test::dataDir();
  if (dir.empty()) GTEST_SKIP() << "../shared/data is absent (set TINLOD_TEST_DATA): real-DEM test skipped";
  const Dem dem = readDem(dir + "/patagonia_coast_S46W066.tif", 1, kQuiet);
  SampleOptions so;
  so.block = 9;  // 160 k vertices: the flat sea is what matters here
  const Tin tin = sampleTin(dem, so, kQuiet);
  const Hierarchy a = buildHierarchy(tin, {}, {}, kQuiet), b = buildHierarchy(tin, {}, {}, kQuiet);
  ASSERT_EQ(a.groups.size(), b.groups.size());
  for (std::size_t i = 0; i < a.groups.size(); i += 97) ASSERT_EQ(a.groups[i].vertex, b.groups[i].vertex);
  const Tin top = a.levelTin(a.coarsest());
  EXPECT_EQ(test::delaunayViolations(top), 0u);
  EXPECT_NEAR(totalArea(top), totalArea(tin), 1e-9 * totalArea(tin));
}

}  // namespace
}  // namespace tinlod
