// SPDX-License-Identifier: GPL-3.0-or-later
// Independent checks of a TIN, written apart from the code they check.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "tinlod/dem.h"
#include "tinlod/hierarchy.h"
#include "tinlod/tin.h"

namespace tinlod::test {

// Vertices seen as fans (a vertex where two triangle fans touch at a point counts
// once per fan), so that a TIN with holes and pinch points is a surface whose Euler
// characteristic V - E + F must equal 2C - B (C components, B boundary loops).
struct Topology {
  std::size_t fans = 0, edges = 0, faces = 0, components = 0, boundaryLoops = 0;
  std::size_t unusedVertices = 0;
  double perimeter = 0;  // length of all boundary edges
  std::string problem;   // empty when every edge has one or two triangles, consistently oriented
  long eulerCharacteristic() const { return long(fans) - long(edges) + long(faces); }
  long expectedEuler() const { return 2 * long(components) - long(boundaryLoops); }
};
Topology analyseTopology(const Tin& tin);

// Triangles not counter-clockwise (zero or negative area), by CGAL's exact orientation.
std::size_t clockwiseTriangles(const Tin& tin);

// (triangle, vertex) pairs where the vertex lies strictly inside the triangle's
// circumcircle, by CGAL's exact in-circle predicate: 0 for a Delaunay TIN.
std::size_t delaunayViolations(const Tin& tin);

// Inner edges (two triangles) whose one triangle's circumcircle holds the other's third
// corner strictly, by CGAL's exact in-circle predicate: 0 for a Delaunay triangulation
// constrained by the TIN's outline.
std::size_t localDelaunayViolations(const Tin& tin);

// (triangle, vertex) pairs where the vertex lies strictly inside the triangle (by CGAL's
// exact orientation): 0 unless triangles overlap.
std::size_t verticesInsideTriangles(const Tin& tin);

// Triangles whose closed footprint in the DEM grid (vertices at their cells' centres)
// holds the centre of a nodata cell, by exact orientation tests.
std::size_t trianglesOverNodata(const Dem& dem, const Tin& tin);

// Vertices placed on a nodata cell.
std::size_t verticesOnNodata(const Dem& dem, const Tin& tin);

// Coverage in grid space (vertices at their cells' centres, one cell = 1), exact.
// Every 2 x 2 block of valid centres is a square the TIN must cover; a block with
// three valid centres, their triangle (half a square). A block with two or three valid
// centres is on the boundary, where a TIN may also cut across the block's other half.
struct GridCoverage {
  double tinCells = 0;       // the TIN's area
  double extentCells = 0;    // full squares plus half squares
  double boundaryBlocks = 0; // blocks with two or three valid centres
};
GridCoverage gridCoverage(const Dem& dem, const Tin& tin);

// The TIN's area with every vertex put back on its cell's centre (transformed like the
// TIN, without jitter): the jitter alone separates it from totalArea(tin).
double unjitteredArea(const Dem& dem, const Tin& tin, const std::string& sourceSrs = "");

// Asserts everything above of a TIN sampled from `dem` with the given jitter (gtest).
void expectValidTin(const Dem& dem, const Tin& tin, double jitter, const std::string& sourceSrs = "");

// Brute force, written apart from the simplifier: each valid cell centre's vertical distance
// to a level, by the first triangle of the level whose closed footprint in the grid holds
// it; NaN where none does. `gridPlace` puts a vertex in the grid as {column, row} (cell
// centres at whole numbers): by its cell and offsets, or from its x and y.
std::vector<double> cellDistances(const Dem& dem, const Hierarchy& h, std::int32_t level,
                                  const std::function<std::array<double, 2>(const TinVertex&)>& gridPlace);

}  // namespace tinlod::test
