// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the varying level-of-detail TIN of a tinlod-tiles catalogue, a tile at a time.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "extracted_lod.h"
#include "tinlod/feedback.h"
#include "tinlod/hierarchy.h"
#include "tinlod/lod_extraction.h"
#include "tinlod/tin.h"

namespace tinlod {

// One tile's part of the output as the output numbers it: `part`'s vertices are numbered
// id[v]; those with isNew[v] appear here first (with consecutive ids, in order) and the
// rest came with an earlier tile (a vertex of a line two tiles share). The outline of
// the vertices on shared lines is left unset, for setOutline to say.
struct LodPiece {
  const ExtractedLod& part;
  const std::vector<VertexId>& id;
  const std::vector<std::uint8_t>& isNew;
};

// Where the output goes, a tile at a time.
class CatalogueLodSink {
 public:
  virtual ~CatalogueLodSink() = default;
  // Before the first piece: the tiles' CRS.
  virtual void start(const std::string& crsWkt, const std::string& crsName) = 0;
  virtual void add(const LodPiece& piece, const ProgressRange& progress) = 0;
  // After the last: the output ids of the shared lines' vertices that are on the union's
  // outline (an edge of theirs has a triangle on one side alone), and how many vertices
  // the union's outline has in all, as a single TIN's file records it.
  virtual void setOutline(const std::vector<VertexId>& sharedOutline, std::size_t outlineVertices) = 0;
};

// What an extraction did, beside its output.
struct CatalogueLodRun {
  std::size_t levelZeroTriangles = 0;
  std::int32_t coarsest = 0;
  double seconds = 0;  // the extractions themselves
  int passes = 1;      // over the tiles, until their lines agreed
};

// The TIN extractLod gives for the catalogue's tiles read as one hierarchy (the same
// triangles; vertices in the same order, rows and columns the whole raster's), handed to
// `sink` a tile at a time, with the memory of one tile: each tile is extracted on its own,
// bringing back the vertices of its shared lines that another tile brought back, until no
// tile brings back a line vertex the others did not (each pass reads only the tiles whose
// lines gained one). The tiles' parts wait in files in `partsFolder` (made, then removed)
// until then. `optionsFor` gets the tiles' CRS (to read centres and regions in) once.
CatalogueLodRun extractCatalogueLod(const std::string& cataloguePath,
                                    const std::function<LodOptions(const std::string& crsWkt)>& optionsFor,
                                    const std::filesystem::path& partsFolder, CatalogueLodSink& sink,
                                    const ProgressRange& progress);

// The same held whole in memory (its parts in a temporary folder meanwhile).
ExtractedLod extractCatalogueLod(const std::string& cataloguePath,
                                 const std::function<LodOptions(const std::string& crsWkt)>& optionsFor,
                                 const ProgressRange& progress);

}  // namespace tinlod
