// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <string>
#include <vector>

#include "tinlod/feedback.h"

namespace tinlod {

// The points of every point feature (and each point of a multipoint) of the first layer
// of a vector file GDAL reads, transformed to the CRS `targetWkt`. A layer without a CRS
// is taken to be in it already (a warning says so). Throws Error naming the file, and
// the type found when the layer or a feature holds lines, polygons or collections.
// Throws Error when a plain path does not exist or its layer is not one of points (checked
// before any long work).
// `what` names the points in messages.
void checkPointsExist(const std::string& path, const std::string& what = "points to keep");

std::vector<std::array<double, 2>> readPoints(const std::string& path, const std::string& targetWkt,
                                              const ProgressRange& progress, const std::string& what = "points to keep");

}  // namespace tinlod
