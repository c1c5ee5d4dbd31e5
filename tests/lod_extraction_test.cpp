// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "mesh_checks.h"
#include "test_support.h"
#include "tinlod/error.h"
#include "tinlod/hierarchy_builder.h"
#include "tinlod/hierarchy_reader.h"
#include "tinlod/hierarchy_writer.h"
#include "tinlod/hierarchy_locator.h"
#include "tinlod/lod_extraction.h"
#include "tinlod/sample_job.h"

namespace tinlod {
namespace {

const ProgressRange kQuiet(Feedback{}, 0, 1);

const Hierarchy& hierarchy() {
  static const Hierarchy h = [] {
    static const Dem dem = test::smallSyntheticDem();
    const Tin tin = sampleTin(dem, SampleOptions{}, kQuiet);
    Hierarchy built = buildHierarchy(tin, dem, {}, HierarchyOptions{}, kQuiet);
    linkGroups(built);
    return built;
  }();
  return h;
}

std::vector<std::uint32_t> sorted(std::vector<std::uint32_t> v) {
  std::sort(v.begin(), v.end());
  return v;
}

Tin asTin(const Hierarchy& h, const std::vector<std::uint32_t>& triangles) {
  Tin tin;
  tin.vertices = h.base.vertices;
  for (std::uint32_t t : triangles) tin.triangles.push_back(h.triangles[t].v);
  return tin;
}

// Conforming: a consistently oriented surface with level 0's holes (a T-junction would add
// boundary edges inside), no triangle over another, and covering level 0's ground but for
// less than a cell along the outline (the outline of each part is that of the level it was
// taken from, within the outline's tolerance).
void expectConforming(const Hierarchy& h, const std::vector<std::uint32_t>& triangles) {
  const Tin tin = asTin(h, triangles);
  const test::Topology t = test::analyseTopology(tin), base = test::analyseTopology(h.base);
  EXPECT_EQ(t.problem, "");
  EXPECT_EQ(t.eulerCharacteristic(), t.expectedEuler());
  EXPECT_EQ(t.boundaryLoops, base.boundaryLoops);
  const double cell = std::sqrt(totalArea(h.base) / double(h.levels[0].cells));
  EXPECT_NEAR(totalArea(tin), totalArea(h.base), cell * base.perimeter);
  EXPECT_EQ(test::clockwiseTriangles(tin), 0u);
  Tin used = tin;
  dropUnusedVertices(used);
  EXPECT_EQ(test::verticesInsideTriangles(used), 0u);  // no triangle over another
}

std::array<double, 2> middle(const Hierarchy& h) {
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const TinVertex& v : h.base.vertices) x0 = std::min(x0, v.x), x1 = std::max(x1, v.x), y0 = std::min(y0, v.y), y1 = std::max(y1, v.y);
  return {(x0 + x1) / 2, (y0 + y1) / 2};
}

// buildHierarchy leaves the groups' links to its caller: extracting or locating without
// them is refused, not read as groups with no triangles.
TEST(LodExtraction, AHierarchyNotLinkedIsRefusedAndOnceLinkedIsTheReadersHierarchy) {
  const Dem dem = test::smallSyntheticDem();
  Hierarchy h = buildHierarchy(sampleTin(dem, SampleOptions{}, kQuiet), dem, {}, HierarchyOptions{}, kQuiet);
  ASSERT_FALSE(h.groups.empty());
  EXPECT_TRUE(h.links.empty());
  LodOptions o;
  o.centres = {middle(h)};
  o.dropoff = 1;
  EXPECT_THROW(extractLod(h, o, kQuiet), Error);
  EXPECT_THROW(HierarchyLocator{h}, Error);
  linkGroups(h);
  // The links a reader makes of the written file, not those of the same code run again.
  const std::string path = test::tempDir() + "/linked.gpkg";
  writeHierarchyGpkg(h, path, GpkgWriteOptions{false, {{"TINLOD_KIND", "hierarchy"}}}, kQuiet);
  const Hierarchy read = readHierarchy(path, kQuiet).hierarchy;
  ASSERT_FALSE(h.links.empty());
  EXPECT_EQ(h.links, read.links);
  EXPECT_EQ(sorted(extractLod(h, o, kQuiet)), sorted(extractLod(read, o, kQuiet)));
}

TEST(LodExtraction, InfiniteDropoffGivesLevelZeroAndZeroDropoffTheCoarsest) {
  const Hierarchy& h = hierarchy();
  ASSERT_GE(h.coarsest(), 5);
  LodOptions o;
  o.centres = {middle(h)};
  o.dropoff = std::numeric_limits<double>::infinity();
  EXPECT_EQ(sorted(extractLod(h, o, kQuiet)), sorted(h.levelTriangles(0)));
  o.dropoff = 0;
  EXPECT_EQ(sorted(extractLod(h, o, kQuiet)), sorted(h.levelTriangles(h.coarsest())));
}

TEST(LodExtraction, DistanceTestIsFineNearTheCentreCoarseFarAndConforming) {
  const Hierarchy& h = hierarchy();
  LodOptions o;
  o.centres = {middle(h)};
  o.dropoff = 250;
  const std::vector<std::uint32_t> out = extractLod(h, o, kQuiet);
  expectConforming(h, out);
  EXPECT_LT(out.size(), h.levelTriangles(0).size());
  EXPECT_GT(out.size(), h.levelTriangles(h.coarsest()).size());
  double nearLevels = 0, farLevels = 0;
  std::size_t nearCount = 0, farCount = 0;
  for (std::uint32_t t : out) {
    const HierarchyTriangle& tri = h.triangles[t];
    // No triangle left whose deleted vertex the test accepts.
    if (tri.group != kNoGroup) {
      const Group& g = h.groups[tri.group];
      const TinVertex& v = h.base.vertices[g.vertex];
      EXPECT_GE(std::hypot(v.x - o.centres[0][0], v.y - o.centres[0][1]), g.level * o.dropoff);
    }
    const TinVertex& a = h.base.vertices[tri.v[0]];
    const double d = std::hypot(a.x - o.centres[0][0], a.y - o.centres[0][1]);
    (d < 1000 ? nearLevels : farLevels) += tri.firstLevel;
    ++(d < 1000 ? nearCount : farCount);
  }
  ASSERT_GT(nearCount, 0u);
  ASSERT_GT(farCount, 0u);
  EXPECT_LT(nearLevels / nearCount + 2, farLevels / farCount);
}

TEST(LodExtraction, ErrorTestKeepsEveryTriangleWithinTheTolerance) {
  const Hierarchy& h = hierarchy();
  for (double tolerance : {0.5, 2.0, 10.0}) {
    LodOptions o;
    o.maxError = tolerance;
    const std::vector<std::uint32_t> out = extractLod(h, o, kQuiet);
    expectConforming(h, out);
    double worst = 0;  // level 0's triangles are as fine as the hierarchy goes
    for (std::uint32_t t : out)
      if (h.triangles[t].group != kNoGroup) worst = std::max(worst, double(h.triangles[t].error));
    EXPECT_LE(worst, tolerance);
  }
  // A tolerance growing with distance: coarser far away.
  LodOptions grow;
  grow.maxError = 0.5;
  grow.errorGrowth = 0.01;
  grow.centres = {middle(h)};
  LodOptions flat;
  flat.maxError = 0.5;
  EXPECT_LT(extractLod(h, grow, kQuiet).size(), extractLod(h, flat, kQuiet).size());
}

TEST(LodExtraction, RegionTestGivesLevelZeroWhereverATriangleMeetsTheRegion) {
  const Hierarchy& h = hierarchy();
  // A strip 30 m wide: few vertices lie in it, yet every triangle across it must be fine.
  const double x0 = middle(h)[0], x1 = x0 + 30;
  LodOptions o;
  o.meetsRegion = [&](const std::array<std::array<double, 2>, 3>& t) {
    const double lo = std::min({t[0][0], t[1][0], t[2][0]}), hi = std::max({t[0][0], t[1][0], t[2][0]});
    return hi >= x0 && lo <= x1;
  };
  const std::vector<std::uint32_t> out = extractLod(h, o, kQuiet);
  expectConforming(h, out);
  std::size_t across = 0;
  for (std::uint32_t t : out) {
    const HierarchyTriangle& tri = h.triangles[t];
    double lo = 1e300, hi = -1e300;
    for (VertexId v : tri.v) lo = std::min(lo, h.base.vertices[v].x), hi = std::max(hi, h.base.vertices[v].x);
    if (hi >= x0 && lo <= x1) {
      ++across;
      EXPECT_EQ(tri.firstLevel, 0);
    }
  }
  EXPECT_GT(across, 50u);
  EXPECT_LT(out.size(), h.levelTriangles(0).size() / 2);
}

TEST(LodExtraction, SeveralCentresAndBadOptions) {
  const Hierarchy& h = hierarchy();
  LodOptions one, two;
  one.dropoff = two.dropoff = 200;
  one.centres = {middle(h)};
  two.centres = {middle(h), {middle(h)[0] - 3000, middle(h)[1] + 2000}};
  const std::vector<std::uint32_t> a = extractLod(h, one, kQuiet), b = extractLod(h, two, kQuiet);
  expectConforming(h, b);
  EXPECT_GT(b.size(), a.size());
  LodOptions none;
  EXPECT_THROW(extractLod(h, none, kQuiet), Error);
  LodOptions noCentre;
  noCentre.dropoff = 100;
  EXPECT_THROW(extractLod(h, noCentre, kQuiet), Error);
  LodOptions negative;
  negative.maxError = -1;
  EXPECT_THROW(extractLod(h, negative, kQuiet), Error);
  LodOptions growthAlone;
  growthAlone.dropoff = 100;
  growthAlone.centres = {middle(h)};
  growthAlone.errorGrowth = 0.1;
  EXPECT_THROW(extractLod(h, growthAlone, kQuiet), Error);
}

}  // namespace
}  // namespace tinlod
