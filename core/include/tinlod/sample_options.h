// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstdint>
#include <string>

#include "tinlod/height_range.h"

namespace tinlod {

// Options of the sampling step, shared by `tinlod sample`, `tinlod build` and the
// QGIS algorithms. Defaults are those of the study.
struct SampleOptions {
  int band = 1;               // raster band holding the heights (1-based)
  int block = 3;              // one random valid cell per block x block cells; 1 takes every cell
  double jitter = 0.99;       // x and y each moved by a uniform offset in [0, jitter) metres
  std::uint64_t seed = 1;     // random seed: the same seed gives the same TIN
  std::string sourceSrs;      // CRS of the DEM when its file has none or a wrong one; empty: the file's
  std::string targetSrs;      // output CRS (any GDAL/PROJ definition); empty: automatic
  HeightRange validHeights;   // heights outside it are undeclared nodata
  bool peaksAndPits = false;  // every strict 3 x 3 peak and pit a vertex too (build -fix_peaks_pits)

  // Throws Error naming the option when a value is out of range.
  void validate() const;
  // The same, for sampling a TIN that is then simplified into a hierarchy, whose levels
  // are measured against the DEM's cells: the jitter must move every vertex off its cell's
  // centre.
  void validateForHierarchy() const;
};

}  // namespace tinlod
