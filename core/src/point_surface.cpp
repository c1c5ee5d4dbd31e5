// SPDX-License-Identifier: GPL-3.0-or-later
#include "point_surface.h"

#include <algorithm>
#include <cmath>

#include "catalogue_hierarchy.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

constexpr std::size_t kTilesKept = 4;

}  // namespace

PointSurface::PointSurface(const std::string& path, const ProgressRange& progress) : progress_(progress) {
  if (isCatalogue(path)) {
    tiles_ = readCatalogue(path);
    warnOfUnfinishedTiles(path, progress);
    const Loaded& first = load(0);
    coarsest_ = first.stored->hierarchy.coarsest();
    crsWkt_ = first.stored->hierarchy.base.crsWkt;
    return;
  }
  loaded_.push_front({0, std::make_unique<StoredHierarchy>(readHierarchy(path, progress)), nullptr});
  loaded_.front().locator = std::make_unique<HierarchyLocator>(loaded_.front().stored->hierarchy);
  coarsest_ = loaded_.front().stored->hierarchy.coarsest();
  crsWkt_ = loaded_.front().stored->hierarchy.base.crsWkt;
}

PointSurface::Loaded& PointSurface::load(std::size_t tile) {
  for (auto it = loaded_.begin(); it != loaded_.end(); ++it)
    if (it->tile == tile) {
      loaded_.splice(loaded_.begin(), loaded_, it);
      return loaded_.front();
    }
  if (loaded_.size() >= kTilesKept) loaded_.pop_back();
  auto stored = std::make_unique<StoredHierarchy>(readCatalogueTile(tiles_[tile], ProgressRange(Feedback{}, 0, 1)));
  ++tilesRead_;
  if (!loaded_.empty() && stored->hierarchy.coarsest() != coarsest_)
    throw Error("tile " + tiles_[tile].name + " ('" + tiles_[tile].file + "') has levels 0 to " +
                std::to_string(stored->hierarchy.coarsest()) + ", the catalogue's other tiles 0 to " +
                std::to_string(coarsest_) + ": they were not built by one job");
  loaded_.push_front({tile, std::move(stored), nullptr});
  loaded_.front().locator = std::make_unique<HierarchyLocator>(loaded_.front().stored->hierarchy);
  return loaded_.front();
}

bool PointSurface::holds(std::size_t tile, double x, double y) const {
  // The catalogue's boxes are the tiles' layer extents, which GDAL rounds to 15 digits: a
  // point just beside a shared line fell between two boxes (5e-9 m at 3e6 m). A box a
  // millionth of a millimetre per metre larger only adds a tile to try: the tile's TIN says.
  const auto& b = tiles_[tile].box;
  const double margin = 1e-9 * std::max({std::abs(b[0]), std::abs(b[1]), std::abs(b[2]), std::abs(b[3]), 1.0});
  return x >= b[0] - margin && x <= b[2] + margin && y >= b[1] - margin && y <= b[3] + margin;
}

std::size_t PointSurface::firstTileAt(double x, double y) const {
  // The boxes of a DEM in degrees overlap in the TIN's CRS (its tiles' edges are curves
  // there): the point is likeliest in the tile whose box it lies deepest in. The first box
  // that held it read 24 tiles for 3,000 points on alps_2x2 as 16 tiles, this 22.
  std::size_t best = tiles_.size();
  double deepest = -INFINITY;
  for (std::size_t t = 0; t < tiles_.size(); ++t) {
    if (!holds(t, x, y)) continue;
    const auto& b = tiles_[t].box;
    const double depth = std::min({x - b[0], b[2] - x, y - b[1], b[3] - y});
    if (depth > deepest) deepest = depth, best = t;
  }
  return tiles_.empty() ? 0 : best;
}

LocatedPoint PointSurface::locate(double x, double y, int level, std::size_t first, std::string& tile) {
  tile.clear();
  if (!tiled()) return loaded_.front().locator->locate(x, y, level);
  // Tiles share their border lines: a point there is in either, with the same height.
  // `first` is likeliest; the other tiles whose boxes hold the point follow.
  const auto in = [&](std::size_t t) {
    if (t >= tiles_.size() || !holds(t, x, y)) return LocatedPoint{};
    const LocatedPoint p = load(t).locator->locate(x, y, level);
    if (p.found()) tile = tiles_[t].name;
    return p;
  };
  if (const LocatedPoint p = in(first); p.found()) return p;
  for (std::size_t t = 0; t < tiles_.size(); ++t)
    if (t != first)
      if (const LocatedPoint p = in(t); p.found()) return p;
  return {};
}

}  // namespace tinlod
