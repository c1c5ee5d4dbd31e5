// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the tiles of a tinlod-tiles catalogue read as one hierarchy, for what needs a
// whole hierarchy at once (accuracy -compare_insert; the tests of the tile-by-tile jobs).
#pragma once

#include <string>
#include <vector>

#include "tile_catalogue.h"
#include "tinlod/feedback.h"
#include "tinlod/hierarchy_reader.h"

namespace tinlod {

// Every finished tile of the catalogue at `path`, as one hierarchy. A vertex on a line two
// tiles share is one vertex; each tile keeps its own group for it (the half of its star on
// that tile's side), at the same level in both, so `Group::vertex` may repeat. A vertex's
// row and column are the whole raster's (the catalogue's tile offsets added). Level
// statistics: vertex and outline counts of the distinct vertices, triangle counts summed,
// the largest error the largest of any tile, RMSE and cells pooled over the tiles (the
// cells on a shared line counted in both tiles). Throws Error when the tiles were not made
// by one job (other levels, CRS or options, or a shared vertex with two heights or levels).
// Memory is that of a whole run over the tiles' extent.
StoredHierarchy readCatalogueHierarchy(const std::string& path, const ProgressRange& progress);

// "tile C,R ('file') <what>: the catalogue's tiles were not built by one job".
std::string notOneJob(const CatalogueTile& tile, const std::string& what);
// The same for a vertex `tile` shares with a tile beside it, at another height or level.
std::string sharedVertexDiffers(const CatalogueTile& tile, const TinVertex& v);

// A tile's level statistics added to those pooled over the tiles before it: triangles,
// cells and times summed, the largest error the largest of them.
void poolLevelStats(LevelStats& pooled, const LevelStats& tile);

// Tiles' levels pooled level by level (the first tile's taken as they are, the others'
// added by poolLevelStats), each level's RMSE pooled over the tiles' cells.
class PooledLevels {
 public:
  // The tile's levels, as many as the first tile's (the caller checks).
  void add(const std::vector<LevelStats>& tile);
  bool empty() const { return levels_.empty(); }
  // The pooled levels so far, their RMSE not yet pooled: for what the caller adds itself.
  std::vector<LevelStats>& levels() { return levels_; }
  // The pooled levels, with their RMSE.
  std::vector<LevelStats> finish();

 private:
  std::vector<LevelStats> levels_;
  std::vector<double> squares_;  // per level, the sum of squared errors over the tiles' cells
};

// A tile's hierarchy file; throws Error naming the tile when it is a single TIN.
StoredHierarchy readCatalogueTile(const CatalogueTile& tile, const ProgressRange& progress);

// Throws Error when the tile's file holds another tile (copied or renamed over it).
void requireOwnTile(const std::string& name, const std::string& file, const HierarchyInfo& info);

// What checkSameJob compares of a tile (and what a job on the tiles keeps of the first):
// its levels, CRS and options, without its vertices and triangles.
Hierarchy jobOf(const Hierarchy& h);

// Throws Error naming `tile` unless its hierarchy `h` has the levels, CRS and options of
// the tiles read `before` it (any of them).
void checkSameJob(const CatalogueTile& tile, const Hierarchy& h, const Hierarchy& before);

// A hierarchy GeoPackage as readHierarchy reads it, or a catalogue as above.
StoredHierarchy readHierarchyOrCatalogue(const std::string& path, const ProgressRange& progress);

// The files read for `path`: the file itself, and a catalogue's finished tiles (which no
// output may replace).
std::vector<std::string> hierarchyInputs(const std::string& path);

}  // namespace tinlod
