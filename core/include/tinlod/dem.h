// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace tinlod {

// Where a DEM read as a window (a tile) lies in the whole raster. Sampling and placing
// vertices by the whole raster's cell indices and geotransform makes a tile's vertices
// those of a run over the whole raster, to the last bit.
struct RasterWindow {
  int colOffset = 0;  // the whole raster's column of the DEM's column 0
  int rowOffset = 0;
  int fullWidth = 0;  // the whole raster's size in cells
  int fullHeight = 0;
  std::array<double, 6> fullGeotransform{0, 1, 0, 0, 0, 1};
};

// A DEM band held in memory: heights row-major from the first stored row, with
// missing cells (declared nodata, NaN, masked) stored as NaN.
struct Dem {
  std::string path;
  int band = 1;
  int width = 0;
  int height = 0;
  // GDAL geotransform: x = gt[0] + col * gt[1], y = gt[3] + row * gt[5] at the
  // cell's upper-left corner; gt[2] and gt[4] are always 0 (no rotation).
  std::array<double, 6> geotransform{0, 1, 0, 0, 0, 1};
  bool hasGeotransform = false;
  std::string crsWkt;  // empty when the file has no CRS
  std::vector<float> z;
  RasterWindow window;  // set by readDem: the whole raster when no window was asked for
  // A tile's: the cells (row * width + col, ascending) of its edges near which a missing
  // cell of the whole raster lies, read beyond the tile; empty for a whole raster. Only the
  // edges are asked about, so only they are listed, not a flag for every cell (17 MB for a
  // 4096 x 4096 tile).
  std::vector<std::size_t> nearNodata;
  // A tile's: the cells of its edges next to a missing cell of the whole raster (among their
  // 8 neighbours, beyond the tile included), listed as nearNodata is: the outline there.
  std::vector<std::size_t> nextToNodata;
  // A tile's: the cells of its edges that are strict peaks or pits of the whole raster
  // (strictPeakOrPit, their 3 x 3 cells read beyond the tile), listed as nearNodata is.
  std::vector<std::size_t> edgePeaksAndPits;

  float at(int row, int col) const { return z[static_cast<std::size_t>(row) * width + col]; }
  bool nearNodataAt(int row, int col) const { return listed(nearNodata, row, col); }
  bool nextToNodataAt(int row, int col) const { return listed(nextToNodata, row, col); }
  bool edgePeakOrPitAt(int row, int col) const { return listed(edgePeaksAndPits, row, col); }
  bool valid(int row, int col) const {
    return row >= 0 && col >= 0 && row < height && col < width && !std::isnan(at(row, col));
  }
  // Georeferenced centre of a cell, in the DEM's own CRS.
  double centreX(int col) const { return geotransform[0] + (col + 0.5) * geotransform[1]; }
  double centreY(int row) const { return geotransform[3] + (row + 0.5) * geotransform[5]; }
  std::size_t validCount() const;
  // The whole raster's cell index of a cell of this DEM.
  std::int64_t globalCol(int col) const { return std::int64_t{window.colOffset} + col; }
  std::int64_t globalRow(int row) const { return std::int64_t{window.rowOffset} + row; }
  // Whether the DEM's last column (row) is shared with a tile beyond it: that tile's
  // blocks start there.
  // The whole raster's geotransform and size (a DEM built in memory is its own whole).
  const std::array<double, 6>& wholeGeotransform() const { return window.fullWidth > 0 ? window.fullGeotransform : geotransform; }
  int wholeWidth() const { return window.fullWidth > 0 ? window.fullWidth : width; }
  int wholeHeight() const { return window.fullHeight > 0 ? window.fullHeight : height; }
  bool sharesLastCol() const { return window.colOffset + width < window.fullWidth; }
  bool sharesLastRow() const { return window.rowOffset + height < window.fullHeight; }

 private:
  bool listed(const std::vector<std::size_t>& cells, int row, int col) const {
    return std::binary_search(cells.begin(), cells.end(), static_cast<std::size_t>(row) * width + col);
  }
};

// Whether a valid cell is higher (or lower) than every valid cell around it, and has one.
bool strictPeakOrPit(const Dem& dem, int row, int col);

}  // namespace tinlod
