// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "tinlod/crs_transform.h"
#include "tinlod/dem.h"
#include "tinlod/feedback.h"
#include "tinlod/greedy_inserter.h"
#include "tinlod/insert_options.h"
#include "tinlod/tin.h"

namespace tinlod {

struct InsertSummary {
  std::size_t candidates = 0, vertices = 0, triangles = 0;
  double maxError = 0;          // the run's own: the largest error of any candidate when it stopped
  double measuredMaxError = 0;  // measured anew at every valid DEM cell the TIN covers
  double rmse = 0;              // over the same cells
  std::size_t measuredCells = 0, uncoveredCells = 0;
  bool holesOpen = false;       // a count limit came before every triangle was off the holes
  double seconds = 0;           // the insertion itself
  std::string crsName;
};

struct InsertedTin {
  Tin tin;
  // Per vertex: its place in the insertion order (1 = first), and the maximum error of the
  // TIN of the vertices before it (see InsertedVertex): a progressive TIN.
  std::vector<std::uint32_t> insertion;
  std::vector<double> errorBefore;
  InsertSummary summary;
  // Per vertex: its DEM cell (column, row), for the independent check.
  std::vector<std::array<double, 2>> cellPositions;
};

// The inserter's input for `dem`: every valid cell, or the vertices of `sampled` (a TIN
// sampled from `dem`, in the CRS `toTin` leads to) when it is not null. `onGrid`: Delaunay
// with square cells rather than on the ground.
InsertGrid makeInsertGrid(const Dem& dem, const CrsTransform& toTin, const Tin* sampled, bool onGrid = false);

// DEM in memory to a greedy-insertion TIN in the metric CRS, measured (see measureInsertedTin).
InsertedTin greedyInsertionTin(const Dem& dem, const InsertOptions& options, const ProgressRange& progress);
// The same without the measuring, which the job runs beside the writing.
InsertedTin insertedTin(const Dem& dem, const InsertOptions& options, const ProgressRange& progress);
// `tin.summary` with the independent check filled in: the TIN's heights at every valid
// cell by a code path of its own (the accuracy rasteriser), the largest error, the RMSE
// and the cells left uncovered.
InsertSummary measureInsertedTin(const Dem& dem, const InsertedTin& tin, const ProgressRange& progress);

// The whole `tinlod insert` job: read, insert, measure, write the GeoPackage (the layers
// of `tinlod sample`, the vertices with their insertion order; a spatial index on the
// vertices too when vertexIndex is set).
InsertSummary runInsertJob(const std::string& demPath, const std::string& outPath, const InsertOptions& options,
                           bool overwrite, const Feedback& feedback, bool vertexIndex = false);

}  // namespace tinlod
