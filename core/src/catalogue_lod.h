// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the varying level-of-detail TIN of a tinlod-tiles catalogue, a tile at a time.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "extracted_lod.h"
#include "tinlod/feedback.h"
#include "tinlod/hierarchy.h"
#include "tinlod/lod_extraction.h"
#include "tinlod/tin.h"

namespace tinlod {

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
