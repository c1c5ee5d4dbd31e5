// SPDX-License-Identifier: GPL-3.0-or-later
// Private: taking a vector layer's coordinates, or points in a given CRS, to a TIN's CRS.
#pragma once

#include <ogrsf_frmts.h>

#include <memory>
#include <string>

#include "tinlod/feedback.h"

namespace tinlod {

// The transformation from `layer`'s CRS to `targetWkt`, or null when none is needed. A
// layer without a CRS is taken to be in the TIN's already, and `what` (e.g. "points to
// keep") warns so.
std::unique_ptr<OGRCoordinateTransformation> transformToTin(OGRLayer& layer, const std::string& targetWkt,
                                                            const std::string& what, const ProgressRange& progress);
// Throws Error naming `what` unless GDAL reads `srs` as a CRS.
void checkSrsText(const std::string& srs, const std::string& what);
// The same from a CRS given as text (any GDAL definition: "EPSG:4326", WKT, PROJ).
std::unique_ptr<OGRCoordinateTransformation> transformToTin(const std::string& srs, const std::string& targetWkt,
                                                            const std::string& what, const ProgressRange& progress);

}  // namespace tinlod
