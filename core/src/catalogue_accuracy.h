// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the accuracy of a tinlod-tiles catalogue, measured a tile at a time.
#pragma once

#include <string>
#include <vector>

#include "tinlod/accuracy_job.h"
#include "tinlod/height_range.h"

namespace tinlod {

// What measureAndWrite reports for the catalogue's tiles read as one hierarchy (the same
// test points, each counted once, and the same sums but for rounding), with the memory of
// one tile rather than of the whole raster: each tile's test points are measured from its
// own hierarchy and its window of the DEM, and the reach of the B-spline surfaces beyond
// its cells is filled from the triangles of the tiles beside it (read through their
// spatial index). The tiles must record their cells (the catalogue's xsize and ysize).
// Greedy insertion (-compare_insert) needs the whole TIN at once and is not done here.
AccuracyReport measureCatalogue(const std::string& demPath, const std::string& cataloguePath, int band,
                                const HeightRange& validHeights, const std::string& sourceSrs,
                                const AccuracyOutputs& outputs, const AccuracyFiles& files, const ProgressRange& progress);

// Throws Error unless enough of the DEM's test points lie on the TIN for the figures to mean
// anything (a DEM beside the TIN's, touching it at a corner, gave one point and a table of
// zeros and NaN); shared with the measurement of one hierarchy file.
void requireTestPoints(const std::vector<LevelAccuracy>& rows, const std::string& demPath);

}  // namespace tinlod
