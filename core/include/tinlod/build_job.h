// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tinlod/accuracy_job.h"
#include "tinlod/dem.h"
#include "tinlod/feedback.h"
#include "tinlod/hierarchy.h"
#include "tinlod/hierarchy_layers.h"
#include "tinlod/tile_borders.h"
#include "tinlod/point_reader.h"
#include "tinlod/sample_options.h"

namespace tinlod {

struct BuildSummary {
  std::size_t originalVertices = 0, coarsestVertices = 0, coarsestTriangles = 0, fixedVertices = 0;
  std::int32_t levels = 0;  // levels above level 0
  double coarsestError = 0;      // against the DEM at every valid cell centre it covers
  double coarsestRmse = 0;
  std::int64_t cellsGivenUp = 0;  // valid cells level 0 covers and the coarsest level does not
  // The DEM's valid cells (0 for a tile), and those level 0 covers: all but data one cell
  // wide beside nodata, which holds no triangle.
  std::size_t validCells = 0;
  std::int64_t levelZeroCells = 0;
  std::uintmax_t fileBytes = 0;
  std::string crsName;
  std::vector<LevelAccuracy> accuracy;  // per level, when accuracy outputs were asked for
  std::vector<std::int32_t> levelViews;  // the levels written as level_N views
};

// Strict local maxima and minima of the DEM (3 x 3 window, valid neighbours) among the
// TIN's vertices: the study's surface-specific points.
std::vector<std::uint8_t> peaksAndPits(const Dem& dem, const Tin& tin);

// What runBuildJob checks before its long work, but the output: the options, the files they
// name, the DEM's band and size (the tile in its grid), its CRS against -s_srs and -t_srs, and
// the jitter against its cells; only two cells of the DEM are read. Throws Error.
void checkBuildJob(const std::string& demPath, const SampleOptions& sample, const HierarchyOptions& options,
                   const AccuracyOutputs& accuracy, const HierarchyLayers& layers, const TileSpec& tile,
                   const Feedback& feedback);

// The whole `tinlod build` job: read, sample, simplify into a hierarchy, write it, and
// measure its accuracy when `accuracy` asks for a raster or a report.
BuildSummary runBuildJob(const std::string& demPath, const std::string& outPath, const SampleOptions& sample,
                         const HierarchyOptions& options, bool overwrite, const Feedback& feedback,
                         const AccuracyOutputs& accuracy = AccuracyOutputs(),
                         const HierarchyLayers& layers = HierarchyLayers(), const TileSpec& tile = TileSpec());

}  // namespace tinlod
