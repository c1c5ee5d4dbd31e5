// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>
#include <string>

#include "tinlod/crs_transform.h"
#include "tinlod/dem.h"
#include "tinlod/feedback.h"
#include "tinlod/gpkg_writer.h"
#include "tinlod/sample_options.h"
#include "tinlod/tin.h"

namespace tinlod {

struct SampleSummary {
  std::size_t validCells = 0;
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  std::size_t outlineVertices = 0;  // on an edge of one triangle: the TIN's outline (a level 0's count)
  double area = 0;  // square metres covered by the TIN
  std::string crsName;
};

// The transform to the TIN's CRS that sampleTin uses, after the checks it makes of the
// options, the CRS and the jitter against the cell size: any window of the DEM (two cells
// across at least, for the jitter) gives the whole raster's.
CrsTransform samplingTransform(const Dem& dem, const SampleOptions& options, const ProgressRange& progress);

// DEM in memory to TIN: sample cells, transform to the metric CRS, perturb, triangulate,
// cut out nodata holes.
Tin sampleTin(const Dem& dem, const SampleOptions& options, const ProgressRange& progress);

// The whole `tinlod sample` job: read, sample, triangulate, write the GeoPackage (with a
// spatial index on the vertices too when vertexIndex is set).
SampleSummary runSampleJob(const std::string& demPath, const std::string& outPath,
                           const SampleOptions& options, bool overwrite, const Feedback& feedback,
                           bool vertexIndex = false);

SampleSummary summarize(const Tin& tin, std::size_t validCells);

}  // namespace tinlod
