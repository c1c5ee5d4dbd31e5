// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <string>
#include <vector>

#include "tinlod/dem.h"
#include "tinlod/dem_reader.h"
#include "tinlod/feedback.h"
#include "tinlod/height_range.h"
#include "tinlod/tile_borders.h"

namespace tinlod {

// Width and height of a raster, in cells.
std::array<int, 2> rasterSize(const std::string& path);

// The window of tile (col, row): tile.size cells from col * size, and the first column of
// the next tile (which the two share). Throws Error naming -tile when it is outside the grid.
CellWindow tileWindow(const std::array<int, 2>& raster, const TileSpec& tile);

// Reads the tile, with Dem::nearNodata listing its edge cells within `pinning` cells of a
// missing cell of the whole raster, Dem::nextToNodata those next to one, and
// Dem::edgePeaksAndPits its edge cells that are
// strict peaks or pits of it: both read from beyond the tile (`pinning` of at least 1), so
// both tiles on a line agree. Throws EmptyTile when it holds fewer than 3 valid cells.
Dem readTile(const std::string& path, int band, const TileSpec& tile, int pinning, const ProgressRange& progress,
             const HeightRange& valid);

}  // namespace tinlod
