// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/insert_options.h"

#include <cmath>

#include "text_and_paths.h"
#include "tinlod/error.h"

namespace tinlod {

std::string candidatesName(InsertCandidates candidates) {
  return candidates == InsertCandidates::Cells ? "cells" : "samples";
}

InsertCandidates parseCandidates(const std::string& name) {
  if (name == "cells") return InsertCandidates::Cells;
  if (name == "samples") return InsertCandidates::Samples;
  throw Error("-candidates must be 'cells' (every valid DEM cell) or 'samples' (the vertices of the sampled TIN), not '" +
              name + "'");
}

void InsertOptions::validate() const {
  if (!std::isfinite(maxError) || maxError < 0)
    throw Error("-max_error must be 0 or more metres (got " + formatNumber(maxError) + "); 0 inserts until the TIN is exact");
  if (maxVertices != 0 && maxVertices < 3)
    throw Error("-max_vertices must be 3 or more (got " + std::to_string(maxVertices) + "), or 0 for no limit");
  if (maxTriangles != 0 && maxTriangles < 1)
    throw Error("-max_triangles must be 1 or more, or 0 for no limit");
  sample.validate();
}

}  // namespace tinlod
