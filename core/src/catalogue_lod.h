// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the varying level-of-detail TIN of a tinlod-tiles catalogue, a tile at a time.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "tinlod/feedback.h"
#include "tinlod/hierarchy.h"
#include "tinlod/lod_extraction.h"
#include "tinlod/tin.h"

namespace tinlod {

// An extracted TIN with what tinlod lod writes beside it.
struct ExtractedLod {
  Tin tin;
  std::vector<double> vertexLevel;                // each vertex's highest level
  std::vector<double> firstLevel, lastLevel;      // each triangle's levels
  std::size_t levelZeroTriangles = 0;
  std::int32_t coarsest = 0;
  double seconds = 0;                             // the extractions themselves
  int passes = 1;                                 // over the tiles, until their lines agreed
};

// Triangles extractLod gave (indices into h.triangles) as a TIN of the vertices they use,
// in the hierarchy's order, with their levels; `kept`, when given, gets each vertex's id in
// the hierarchy.
ExtractedLod extractedLod(const Hierarchy& h, const std::vector<std::uint32_t>& triangles,
                          std::vector<VertexId>* kept = nullptr);

// The TIN extractLod gives for the catalogue's tiles read as one hierarchy (the same
// triangles; vertices in the same order, rows and columns the whole raster's), with the
// memory of one tile and of the output: each tile is extracted on its own, bringing back
// the vertices of its shared lines that another tile brought back, until no tile brings
// back a line vertex the others did not (each pass reads only the tiles whose lines gained
// one). `optionsFor` gets the tiles' CRS (to read centres and regions in) once.
ExtractedLod extractCatalogueLod(const std::string& cataloguePath,
                                 const std::function<LodOptions(const std::string& crsWkt)>& optionsFor,
                                 const ProgressRange& progress);

}  // namespace tinlod
