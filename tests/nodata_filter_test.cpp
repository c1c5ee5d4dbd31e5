// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>

#include "mesh_checks.h"
#include "test_support.h"
#include "tinlod/error.h"
#include "tinlod/sample_job.h"

namespace tinlod {
namespace {

const Feedback kQuiet;
const ProgressRange kRange(kQuiet, 0, 1);

// Every cell a vertex, jitter small against the 10 m cells: the TIN's triangles are
// halves of the grid's squares and their count is known exactly.
Tin everyCell(const Dem& dem) {
  SampleOptions o;
  o.block = 1;
  o.jitter = 0.3;
  return sampleTin(dem, o, kRange);
}

void expectHolesRespected(const Dem& dem, const Tin& tin, double jitter = 0.3) {
  test::expectValidTin(dem, tin, jitter);
}

// With every cell a vertex, a triangle's grid footprint is half a square: the TIN
// covers the valid extent exactly.
void expectExactExtent(const Dem& dem, const Tin& tin) {
  const test::GridCoverage g = test::gridCoverage(dem, tin);
  EXPECT_DOUBLE_EQ(g.tinCells, g.extentCells);
}

TEST(NodataFilter, FullGridGivesTwoTrianglesPerSquare) {
  const Dem dem = test::makeDem(9, 9, 10, [](int r, int c) { return float(r * c); });
  const Tin tin = everyCell(dem);
  EXPECT_EQ(tin.triangles.size(), 128u);
  EXPECT_EQ(tin.vertices.size(), 81u);
  expectHolesRespected(dem, tin);
  expectExactExtent(dem, tin);
}

TEST(NodataFilter, SingleNodataCellIsAHole) {
  const Dem dem = test::makeDem(9, 9, 10, [](int r, int c) { return r == 4 && c == 4 ? NAN : 1.0f; });
  const Tin tin = everyCell(dem);
  // The four squares around the hole keep one triangle each: 128 - 8 + 4.
  EXPECT_EQ(tin.triangles.size(), 124u);
  const test::Topology t = test::analyseTopology(tin);
  EXPECT_EQ(t.boundaryLoops, 2u);
  EXPECT_EQ(t.eulerCharacteristic(), 0);
  expectHolesRespected(dem, tin);
  expectExactExtent(dem, tin);
}

TEST(NodataFilter, NodataColumnSplitsTheTinInTwo) {
  const Dem dem = test::makeDem(10, 9, 10, [](int, int c) { return c == 4 ? NAN : 1.0f; });
  const Tin tin = everyCell(dem);
  EXPECT_EQ(tin.triangles.size(), 48u + 64u);  // 3 x 8 and 4 x 8 squares
  const test::Topology t = test::analyseTopology(tin);
  EXPECT_EQ(t.components, 2u);
  expectHolesRespected(dem, tin);
  expectExactExtent(dem, tin);
}

TEST(NodataFilter, MissingCornerCellLeavesHalfASquare) {
  const Dem dem = test::makeDem(3, 3, 10, [](int r, int c) { return r == 0 && c == 0 ? NAN : 1.0f; });
  const Tin tin = everyCell(dem);
  EXPECT_EQ(tin.triangles.size(), 7u);
  expectHolesRespected(dem, tin);
  expectExactExtent(dem, tin);
}

TEST(NodataFilter, RingOfNodataAroundAnIslandKeepsBothApart) {
  // A lake of nodata with a valid island in it: the island is its own component.
  const Dem dem = test::makeDem(40, 40, 10, [](int r, int c) {
    const double d = std::hypot(r - 20, c - 20);
    return d > 6 && d < 12 ? NAN : float(d);
  });
  SampleOptions o;  // the study's 3 x 3 sampling
  const Tin tin = sampleTin(dem, o, kRange);
  const test::Topology t = test::analyseTopology(tin);
  EXPECT_EQ(t.components, 2u);
  EXPECT_EQ(t.boundaryLoops, 3u);
  expectHolesRespected(dem, tin, o.jitter);
}

TEST(NodataFilter, IsolatedValidCellsAreLeftOut) {
  const Dem dem = test::makeDem(9, 9, 10, [](int r, int c) { return (r < 4 || (r == 7 && c == 7)) ? 1.0f : NAN; });
  const Tin tin = everyCell(dem);
  for (const TinVertex& v : tin.vertices) EXPECT_LT(v.row, 4);
  EXPECT_EQ(tin.triangles.size(), 2u * 8u * 3u);
  expectHolesRespected(dem, tin);
}

TEST(NodataFilter, ValidCellsInALineGiveNoTriangleError) {
  const Dem dem = test::makeDem(9, 9, 10, [](int r, int) { return r == 4 ? 1.0f : NAN; });
  try {
    everyCell(dem);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no triangle"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tinlod
