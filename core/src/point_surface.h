// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <list>
#include <memory>
#include <string>
#include <vector>

#include "tile_catalogue.h"
#include "tinlod/feedback.h"
#include "tinlod/hierarchy_locator.h"
#include "tinlod/hierarchy_reader.h"

namespace tinlod {

// Where points are located: one hierarchy, or a catalogue's tiles, whose hierarchies are
// read as points fall in them and kept a few at a time (memory bounded by the tiles, not
// by the catalogue).
class PointSurface {
 public:
  PointSurface(const std::string& path, const ProgressRange& progress);
  bool tiled() const { return !tiles_.empty(); }
  int coarsest() const { return coarsest_; }
  const std::string& crsWkt() const { return crsWkt_; }
  // The tile whose extent holds the point deepest inside it (likeliest its TIN's where the
  // extents overlap, as a DEM in degrees' do in the TIN's CRS), or the tile count when none
  // does (and 0 for one hierarchy): points located in this order read each tile about once,
  // where points in any order would read a tile again and again.
  std::size_t firstTileAt(double x, double y) const;
  // The point at `level`, looked for in tile `first` (firstTileAt), then in the other tiles
  // whose extents hold it; `tile` is set to the tile's name ("" for one hierarchy).
  LocatedPoint locate(double x, double y, int level, std::size_t first, std::string& tile);
  // The tile hierarchies read so far.
  std::size_t tilesRead() const { return tilesRead_; }

 private:
  struct Loaded {
    std::size_t tile;
    std::unique_ptr<StoredHierarchy> stored;
    std::unique_ptr<HierarchyLocator> locator;
  };
  Loaded& load(std::size_t tile);
  bool holds(std::size_t tile, double x, double y) const;

  std::vector<CatalogueTile> tiles_;
  std::list<Loaded> loaded_;  // most recently used first
  int coarsest_ = 0;
  std::size_t tilesRead_ = 0;
  std::string crsWkt_;
  ProgressRange progress_;
};

}  // namespace tinlod
