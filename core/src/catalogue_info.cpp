// SPDX-License-Identifier: GPL-3.0-or-later
#include "catalogue_info.h"

#include <cmath>

#include "catalogue_hierarchy.h"
#include "tile_catalogue.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

HierarchyInfo finishedTileInfo(const TileStatus& tile) {
  try {
    HierarchyInfo info = readHierarchyInfo(tile.file);
    if (info.kind != "hierarchy") throw Error("it is a single TIN (" + info.kind + "), not a hierarchy");
    return info;
  } catch (const Error& e) {
    throw Error("tile " + tile.name + " of the catalogue ('" + tile.file + "'): " + e.what());
  }
}

// Adds a finished tile's levels to the catalogue's; `squares` gets each level's sum of
// squared errors over the tile's cells, for the pooled RMSE.
void addTileLevels(const TileStatus& tile, const std::vector<LevelStats>& levels, HierarchyInfo& info,
                   std::vector<double>& squares) {
  const bool first = squares.empty();
  if (first) {
    info.levels = levels;
    squares.assign(levels.size(), 0);
  } else if (levels.size() != info.levels.size()) {
    throw Error("tile " + tile.name + " ('" + tile.file + "') has levels 0 to " + std::to_string(levels.size() - 1) +
                ", the tiles before it 0 to " + std::to_string(info.levels.size() - 1) +
                ": the catalogue's tiles were not built by one job");
  }
  for (std::size_t L = 0; L < levels.size(); ++L) {
    LevelStats& pooled = info.levels[L];
    if (!first) {
      poolLevelStats(pooled, levels[L]);
      pooled.vertices += levels[L].vertices, pooled.deleted += levels[L].deleted;
    }
    // A tile's outline runs along the lines it shares: its count says nothing of the union's.
    pooled.outlineVertices = 0;
    squares[L] += levels[L].rmse * levels[L].rmse * double(levels[L].cells);
  }
}

}  // namespace

void addCatalogueContents(HierarchyInfo& info) {
  std::vector<double> squares;
  for (const TileStatus& tile : readTileStatuses(info.path)) {
    ++info.tileStatuses[tile.status];
    if (tile.status == "failed")
      info.failedTiles.push_back(tile.name + ": " + (tile.error.empty() ? "no message" : tile.error));
    if (tile.status != "done" || tile.file.empty()) continue;
    const HierarchyInfo tileInfo = finishedTileInfo(tile);
    addTileLevels(tile, tileInfo.levels, info, squares);
    info.tileBytes += tileInfo.bytes;
  }
  for (std::size_t L = 0; L < info.levels.size(); ++L)
    info.levels[L].rmse = info.levels[L].cells > 0 ? std::sqrt(squares[L] / double(info.levels[L].cells)) : 0;
}

}  // namespace tinlod
