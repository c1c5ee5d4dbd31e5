// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tinlod {

using VertexId = std::uint32_t;

struct TinVertex {
  double x = 0;  // metric CRS of the TIN
  double y = 0;
  double z = 0;
  std::int32_t row = 0;  // source DEM cell
  std::int32_t col = 0;
  // The jitter in cell units: the vertex lies at (col + dcol, row + drow) in the DEM's
  // grid, where cell centres are at whole numbers. The simplifier measures each level
  // against the DEM's cells from there.
  float dcol = 0;
  float drow = 0;
  bool outline = false;  // on the edge of the valid area (raster edge or nodata)
};

// Counter-clockwise in the TIN's x/y plane.
using Triangle = std::array<VertexId, 3>;

// A triangulated irregular network: vertex ids are indices into `vertices`.
struct Tin {
  std::vector<TinVertex> vertices;
  std::vector<Triangle> triangles;
  // Optional, as the sampler's triangulation found them: for each triangle, the triangle
  // across the edge opposite each corner, or -1 on the outline. Empty when unknown; code
  // that changes `triangles` must update or clear it (the simplifier checks it and links
  // the triangles itself when it does not fit).
  std::vector<std::array<std::int32_t, 3>> neighbours;
  std::string crsWkt;   // the metric CRS of x and y; empty when the DEM had none
  std::string crsName;  // for messages: "WGS 84 / UTM zone 32N (EPSG:32632)"
};

double triangleArea(const Tin& tin, const Triangle& t);  // signed, positive when CCW

// Drops the vertices no triangle uses and renumbers the triangles; the kept vertices keep
// their order. Returns each kept vertex's index before, for data held beside the TIN.
std::vector<VertexId> dropUnusedVertices(Tin& tin);
double totalArea(const Tin& tin);
// Renumbers the vertices along a Z-order curve and orders the triangles by their
// smallest vertex. Vertices near each other then have near ids and their triangles lie
// side by side in memory, which every pass over the TIN's stars reads in cache: the
// simplifier runs a fifth faster than on the sampler's row-by-row order.
void orderSpatially(Tin& tin);

}  // namespace tinlod
