// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "tinlod/feedback.h"
#include "tinlod/lod_extraction.h"

namespace tinlod {

// `tinlod lod`: the tests of LodOptions, with centres and a region read from files.
struct LodJobOptions {
  LodOptions lod;
  // The CRS lod.centres are given in (any GDAL definition: "EPSG:4326", WKT); empty: the
  // hierarchy's own. They are transformed to the hierarchy's CRS (a catalogue's tiles').
  std::string centresSrs;
  std::string centresPath;  // a point layer: every point a centre of detail (added to lod.centres)
  std::string regionPath;   // a polygon layer: every vertex inside it restored
};

struct LodSummary {
  std::size_t vertices = 0, triangles = 0;
  std::vector<std::size_t> trianglesPerLevel;  // by each triangle's first level
  std::size_t levelZeroTriangles = 0;          // for comparison
  std::string crsName;
  double seconds = 0;                          // the extraction itself
};

// Reads a hierarchy GeoPackage (tinlod build), extracts the varying level-of-detail TIN
// and writes it as a GeoPackage TIN ('vertices', and 'triangles' with each triangle's
// first and last level) in the hierarchy's CRS; a spatial index on the vertices too when
// vertexIndex is set. Fails before the long work on bad options.
LodSummary runLodJob(const std::string& hierarchyPath, const std::string& outPath, const LodJobOptions& options,
                     bool overwrite, const Feedback& feedback, bool vertexIndex = false);

}  // namespace tinlod
