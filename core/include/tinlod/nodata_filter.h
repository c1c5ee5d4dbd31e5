// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>

#include "tinlod/dem.h"
#include "tinlod/feedback.h"
#include "tinlod/tin.h"

namespace tinlod {

// Cuts nodata holes out of a TIN sampled from `dem`: drops every triangle whose
// closed footprint in the DEM grid (its vertices' cell centres) contains the centre
// of a missing or off-raster cell, then drops vertices left in no triangle and
// renumbers the rest. Returns the number of vertices dropped.
std::size_t removeTrianglesOverNodata(const Dem& dem, Tin& tin, const ProgressRange& progress);

}  // namespace tinlod
