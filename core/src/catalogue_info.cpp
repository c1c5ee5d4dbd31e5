// SPDX-License-Identifier: GPL-3.0-or-later
#include "catalogue_info.h"

#include "catalogue_hierarchy.h"
#include "tile_catalogue.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

HierarchyInfo finishedTileInfo(const TileStatus& tile) {
  requireTileFile(tile.name, tile.file);
  try {
    // Its own tiles unread: a catalogue named as its own tile would be read without end.
    HierarchyInfo info = readHierarchyInfo(tile.file, false);
    if (info.kind == "catalogue") throw Error("it is a tinlod-tiles catalogue, not a tile");
    if (info.kind != "hierarchy") throw Error("it is a single TIN (" + info.kind + "), not a hierarchy");
    requireOwnTile(tile.name, tile.file, info);
    return info;
  } catch (const Error& e) {
    const std::string why = e.what();
    if (why.rfind("tile " + tile.name + " ", 0) == 0) throw;  // it names the tile already
    throw Error("tile " + tile.name + " of the catalogue ('" + tile.file + "'): " + why);
  }
}

// Adds a finished tile's levels to the catalogue's, its vertices and deleted vertices summed
// too (a vertex on a line two tiles share counted in each).
void addTileLevels(const TileStatus& tile, const std::vector<LevelStats>& levels, PooledLevels& pooled) {
  if (!pooled.empty()) {
    std::vector<LevelStats>& sums = pooled.levels();
    if (levels.size() != sums.size())
      throw Error("tile " + tile.name + " ('" + tile.file + "') has levels 0 to " + std::to_string(levels.size() - 1) +
                  ", the tiles before it 0 to " + std::to_string(sums.size() - 1) +
                  ": the catalogue's tiles were not built by one job");
    for (std::size_t L = 0; L < levels.size(); ++L)
      sums[L].vertices += levels[L].vertices, sums[L].deleted += levels[L].deleted;
  }
  pooled.add(levels);
}

}  // namespace

void addCatalogueContents(HierarchyInfo& info) {
  PooledLevels pooled;
  for (const TileStatus& tile : readTileStatuses(info.path)) {
    ++info.tileStatuses[tile.status];
    if (tile.status == "failed")
      info.failedTiles.push_back(tile.name + ": " + (tile.error.empty() ? "no message" : tile.error));
    if (tile.status != "done" || tile.file.empty()) continue;
    // One tile lost or damaged: the rest is still described, and the tile named.
    HierarchyInfo tileInfo;
    try {
      tileInfo = finishedTileInfo(tile);
    } catch (const Error& e) {
      info.unreadableTiles.push_back(e.what());  // it names the tile
      continue;
    }
    addTileLevels(tile, tileInfo.levels, pooled);
    info.tileBytes += tileInfo.bytes;
  }
  info.levels = pooled.finish();
  // A tile's outline runs along the lines it shares: its count says nothing of the union's.
  for (LevelStats& l : info.levels) l.outlineVertices = 0;
}

}  // namespace tinlod
