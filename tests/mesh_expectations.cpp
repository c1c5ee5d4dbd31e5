// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include "mesh_checks.h"

namespace tinlod::test {

void expectValidTin(const Dem& dem, const Tin& tin, double jitter, const std::string& sourceSrs) {
  EXPECT_EQ(verticesOnNodata(dem, tin), 0u);
  EXPECT_EQ(trianglesOverNodata(dem, tin), 0u);
  EXPECT_EQ(clockwiseTriangles(tin), 0u);
  EXPECT_EQ(delaunayViolations(tin), 0u);
  const Topology t = analyseTopology(tin);
  EXPECT_EQ(t.problem, "");
  EXPECT_EQ(t.unusedVertices, 0u);
  EXPECT_EQ(t.eulerCharacteristic(), t.expectedEuler())
      << t.fans << " - " << t.edges << " + " << t.faces << ", " << t.components << " components, "
      << t.boundaryLoops << " boundary loops";
  const GridCoverage g = gridCoverage(dem, tin);
  EXPECT_GE(g.tinCells, g.extentCells);
  EXPECT_LE(g.tinCells, g.extentCells + 0.5 * g.boundaryBlocks);
  EXPECT_NEAR(totalArea(tin), unjitteredArea(dem, tin, sourceSrs), 1.5 * jitter * t.perimeter + 1e-6);
}

}  // namespace tinlod::test
