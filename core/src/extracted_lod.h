// SPDX-License-Identifier: GPL-3.0-or-later
// Private: a varying level-of-detail TIN as tinlod lod writes it, from one hierarchy or
// from a catalogue's tiles.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "tinlod/hierarchy.h"
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

}  // namespace tinlod
