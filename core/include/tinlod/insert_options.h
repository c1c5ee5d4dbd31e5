// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>
#include <string>

#include "tinlod/sample_options.h"

namespace tinlod {

// Which points greedy insertion may insert.
enum class InsertCandidates {
  Cells,    // every valid DEM cell: DEM to TIN
  Samples,  // the vertices of the sampled TIN (`tinlod sample`): the study's comparator
};

std::string candidatesName(InsertCandidates candidates);
InsertCandidates parseCandidates(const std::string& name);  // throws Error listing the choices

// Options of greedy insertion, shared by `tinlod insert`, the QGIS algorithm and the
// experiment. It stops at whichever limit comes first.
struct InsertOptions {
  InsertCandidates candidates = InsertCandidates::Cells;
  double maxError = 1;           // metres: every candidate within this of the TIN; 0: until exact
  std::size_t maxVertices = 0;   // 0: no limit
  std::size_t maxTriangles = 0;  // 0: no limit
  // Delaunay on the DEM's grid with square cells (as delatin and most tools do) instead of
  // on the ground in metres. Differs only where cells are not square on the ground (a
  // geographic DEM away from the equator).
  bool delaunayOnGrid = false;
  SampleOptions sample;          // band and CRSs; block, jitter and seed for the sampled candidates

  void validate() const;  // throws Error naming the option
};

}  // namespace tinlod
