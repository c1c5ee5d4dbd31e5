// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/tile_reader.h"

#include <gdal_priv.h>

#include <algorithm>

#include "gdal_handles.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

// The cells on the edge of the window (as Dem's lists of a tile hold them: row * width +
// col, ascending) for which `wanted(row, col)` holds: only the edges are asked about (the
// border lines), so a scan costs the window's perimeter.
template <class Wanted>
std::vector<std::size_t> edgeCellsWhere(const CellWindow& w, Wanted wanted) {
  std::vector<std::size_t> cells;
  auto test = [&](int r, int c) {
    if (wanted(r, c)) cells.push_back(static_cast<std::size_t>(r) * w.xsize + c);
  };
  for (int c = 0; c < w.xsize; ++c) test(0, c);
  for (int r = 1; r + 1 < w.ysize; ++r) test(r, 0), test(r, w.xsize - 1);
  if (w.ysize > 1)
    for (int c = 0; c < w.xsize; ++c) test(w.ysize - 1, c);
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  return cells;
}

// Dem::nearNodata of the window, which sits at (col0, row0) in `wide`: its edge cells within
// `reach` cells (either way, on the raster) of a missing cell.
std::vector<std::size_t> missingNearEdges(const Dem& wide, const CellWindow& w, int col0, int row0, int reach) {
  return edgeCellsWhere(w, [&](int r, int c) {
    for (int dr = -reach; dr <= reach; ++dr)
      for (int dc = -reach; dc <= reach; ++dc) {
        const int rr = row0 + r + dr, cc = col0 + c + dc;
        if (rr >= 0 && cc >= 0 && rr < wide.height && cc < wide.width && !wide.valid(rr, cc)) return true;
      }
    return false;
  });
}

// Dem::edgePeaksAndPits of the window: its edge cells that are strict peaks or pits of the
// whole raster around them.
std::vector<std::size_t> edgePeaksAndPits(const Dem& wide, const CellWindow& w, int col0, int row0) {
  return edgeCellsWhere(w, [&](int r, int c) { return strictPeakOrPit(wide, row0 + r, col0 + c); });
}

}  // namespace

std::array<int, 2> rasterSize(const std::string& path) {
  const DatasetPtr ds = openReadOnly(path, GDAL_OF_RASTER);
  if (!ds) throw Error("cannot open '" + path + "' as a raster");
  return {ds->GetRasterXSize(), ds->GetRasterYSize()};
}

CellWindow tileWindow(const std::array<int, 2>& raster, const TileSpec& tile) {
  const int across = TileSpec::count(raster[0], tile.size), down = TileSpec::count(raster[1], tile.size);
  if (tile.col < 0 || tile.row < 0 || tile.col >= across || tile.row >= down)
    throw Error("-tile " + std::to_string(tile.col) + "," + std::to_string(tile.row) + " is outside the grid: with -tile_size " +
                std::to_string(tile.size) + " the raster's " + std::to_string(raster[0]) + " x " + std::to_string(raster[1]) +
                " cells make " + std::to_string(across) + " x " + std::to_string(down) + " tiles, numbered from 0,0");
  CellWindow w;
  w.xoff = tile.col * tile.size, w.yoff = tile.row * tile.size;
  w.xsize = std::min(w.xoff + tile.size, raster[0] - 1) - w.xoff + 1;
  w.ysize = std::min(w.yoff + tile.size, raster[1] - 1) - w.yoff + 1;
  w.xsize = std::max(1, std::min(w.xsize, raster[0] - w.xoff));
  w.ysize = std::max(1, std::min(w.ysize, raster[1] - w.yoff));
  return w;
}

Dem readTile(const std::string& path, int band, const TileSpec& tile, int pinning, const ProgressRange& progress,
             const HeightRange& valid) {
  const std::array<int, 2> raster = rasterSize(path);
  const CellWindow w = tileWindow(raster, tile);
  // Read `pinning` cells more on every side the raster goes on, to see missing cells there.
  CellWindow wide;
  wide.xoff = std::max(0, w.xoff - pinning), wide.yoff = std::max(0, w.yoff - pinning);
  wide.xsize = std::min(raster[0], w.xoff + w.xsize + pinning) - wide.xoff;
  wide.ysize = std::min(raster[1], w.yoff + w.ysize + pinning) - wide.yoff;
  Dem dem = readDemWindow(path, band, wide, progress, valid);
  std::vector<std::size_t> near = missingNearEdges(dem, w, w.xoff - wide.xoff, w.yoff - wide.yoff, pinning);
  std::vector<std::size_t> next = missingNearEdges(dem, w, w.xoff - wide.xoff, w.yoff - wide.yoff, 1);
  std::vector<std::size_t> extremes = edgePeaksAndPits(dem, w, w.xoff - wide.xoff, w.yoff - wide.yoff);
  cropDem(dem, w.xoff - wide.xoff, w.yoff - wide.yoff, w.xsize, w.ysize);
  dem.nearNodata = std::move(near);  // by cell of the tile, as cropped
  dem.nextToNodata = std::move(next);
  dem.edgePeaksAndPits = std::move(extremes);
  const std::size_t count = dem.validCount();
  if (count < 3)
    throw EmptyTile("tile " + std::to_string(tile.col) + "," + std::to_string(tile.row) + " of '" + path + "' has " +
                    std::to_string(count) + " valid cell(s)");
  return dem;
}

}  // namespace tinlod
