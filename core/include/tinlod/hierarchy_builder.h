// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "tinlod/dem.h"
#include "tinlod/feedback.h"
#include "tinlod/hierarchy.h"
#include "tinlod/tile_borders.h"

namespace tinlod {

using PointXY = std::array<double, 2>;

// Simplifies `base`, sampled from `dem`, level by level into a hierarchy, measuring every
// level against the DEM at each valid cell centre it covers (TinVertex::row, col, dcol
// and drow say where each vertex lies in the DEM's grid). Vertices flagged in `fixed`, the
// vertices nearest to `keep` (points in the TIN's CRS; points off the TIN's data are
// ignored with a warning) and the raster's corners are never deleted; a vertex on the
// outline of the data or of a hole goes only while the outline moves by at most the
// options' tolerance, and never out over nodata (none goes with keepOutline). The
// hierarchy keeps `base`: pass std::move(tin) when the TIN is not needed afterwards.
// With `tile`, `dem` is a tile of a raster: its border vertices go only by the border rule,
// and exactly tile->levels levels are made. The groups are not linked: call linkGroups
// before extracting or locating.
Hierarchy buildHierarchy(Tin base, const Dem& dem, std::vector<std::uint8_t> fixed, const HierarchyOptions& options,
                         const ProgressRange& progress, const std::vector<PointXY>& keep = {},
                         const TileBorders* tile = nullptr);

}  // namespace tinlod
