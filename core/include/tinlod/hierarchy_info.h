// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "tinlod/hierarchy.h"

namespace tinlod {

// What a tinlod GeoPackage says of itself, for `tinlod info`.
struct HierarchyInfo {
  std::string path;
  std::string kind;  // "hierarchy", "tin", "lod" or "catalogue"
  std::string crsName;
  std::uintmax_t bytes = 0;
  std::map<std::string, std::string> metadata;  // TINLOD_* items, without the prefix, lower case
  // One for a plain TIN. A catalogue's are its finished tiles' rows added up (maximum
  // error the largest, RMSE over their cells), so a vertex or cell on a line two tiles
  // share is counted in each; its triangles are exact.
  std::vector<LevelStats> levels;
  std::vector<std::string> layers;
  // A catalogue's tiles: how many have each status, why each failed tile failed ("C,R: why"),
  // and the bytes of the finished tiles' files (`bytes` is the catalogue's own).
  std::map<std::string, std::size_t> tileStatuses;
  std::vector<std::string> failedTiles;
  // Its finished tiles it cannot read, each as the reason (which names the tile): the
  // levels are then the other tiles'.
  std::vector<std::string> unreadableTiles;
  std::uintmax_t tileBytes = 0;
};

// Throws Error when the file is not a GeoPackage made by tinlod. A tinlod-tiles catalogue's
// finished tiles it cannot read are listed in unreadableTiles; without `withTiles` a
// catalogue's tiles are not read at all (its kind and metadata alone), as a reader that
// refuses catalogues, or takes a file for a tile, needs.
HierarchyInfo readHierarchyInfo(const std::string& path, bool withTiles = true);

// tinlod-tiles draws each level across the tiles as <stem>_levels/level_K.vrt beside the
// catalogue <stem>.gpkg: for such a path (any .vrt in a <stem>_levels folder), the
// catalogue's path, whether it exists or not; "" for any other.
std::string catalogueOfLevelFile(const std::string& path);

std::string toJson(const HierarchyInfo& info);
std::string toText(const HierarchyInfo& info);

}  // namespace tinlod
