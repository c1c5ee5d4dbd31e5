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
  // The point at `level`; `tile` is set to the tile's name ("" for one hierarchy).
  LocatedPoint locate(double x, double y, int level, std::string& tile);

 private:
  struct Loaded {
    std::size_t tile;
    std::unique_ptr<StoredHierarchy> stored;
    std::unique_ptr<HierarchyLocator> locator;
  };
  Loaded& load(std::size_t tile);

  std::vector<CatalogueTile> tiles_;
  std::list<Loaded> loaded_;  // most recently used first
  int coarsest_ = 0;
  std::string crsWkt_;
  ProgressRange progress_;
};

}  // namespace tinlod
