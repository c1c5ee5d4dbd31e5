// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace tinlod {

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

  float at(int row, int col) const { return z[static_cast<std::size_t>(row) * width + col]; }
  bool valid(int row, int col) const {
    return row >= 0 && col >= 0 && row < height && col < width && !std::isnan(at(row, col));
  }
  // Georeferenced centre of a cell, in the DEM's own CRS.
  double centreX(int col) const { return geotransform[0] + (col + 0.5) * geotransform[1]; }
  double centreY(int row) const { return geotransform[3] + (row + 0.5) * geotransform[5]; }
  std::size_t validCount() const;
};

}  // namespace tinlod
