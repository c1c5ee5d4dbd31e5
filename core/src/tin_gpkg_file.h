// SPDX-License-Identifier: GPL-3.0-or-later
// Private: a TIN's GeoPackage written in steps: its two layers when made, its vertex rows
// (all at once, or batch by batch while a greedy insertion makes the vertices), then its
// triangle rows, spatial indexes and metadata.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "gpkg_feature_rows.h"
#include "gpkg_output.h"
#include "tin_layers.h"
#include "tinlod/gpkg_writer.h"
#include "tinlod/tin.h"

namespace tinlod {

class TinGpkgFile {
 public:
  // Makes the layers: the common fields, then `vertexExtra` and `triangleExtra` (only
  // their names and kinds are read here).
  TinGpkgFile(const StagedFile& file, const GpkgWriteOptions& options, const std::string& crsWkt,
              const std::vector<ExtraField>& vertexExtra, const std::vector<ExtraField>& triangleExtra);

  // The vertices layer's rows (fields: vertexFields(), then the extra ones) and the srs_id
  // of its geometry blobs; the writer of the rows finishes them (writeVertices does).
  GpkgFeatureRows& vertexRows() { return *vertexRows_; }
  std::int32_t srsId() const { return srsId_; }
  SqliteDatabase& database() { return out_.database(); }
  // Empties the vertices layer for its rows to be written again (rows of vertices that
  // turned out not to be the TIN's).
  void clearVertexRows();
  // Packs the triangles' R-tree (and the vertices' when asked) on another core while the
  // rows are written.
  void indexLater(const Tin& tin);
  // The triangle rows after the vertex rows, over `rows`; then the indexes and the commit.
  void finish(const Tin& tin, const std::vector<ExtraField>& triangleExtra, const ProgressRange& rows,
              const ProgressRange& rest);

  // For a writer that has the triangles a batch at a time too: the triangles layer's rows
  // (fields: triangleFields(), then the extra ones), written with writeTriangleRows; then
  // finishRows() with the layers' boxes in fid order (the vertices' only with a vertex
  // index) ends both layers, writes the indexes and commits.
  GpkgFeatureRows& triangleRows();
  void finishRows(std::vector<RtreeBox> vertexBoxes, std::vector<RtreeBox> triangleBoxes, const ProgressRange& progress);
  bool vertexIndex() const { return vertexIndex_; }

 private:
  GpkgOutput out_;
  bool vertexIndex_;
  std::vector<std::string> vertexNames_, triangleNames_;  // the layers' fields, as made
  std::optional<GpkgFeatureRows> vertexRows_, triangleRows_;
  std::int32_t srsId_ = 0;
};

// Sets the extra fields, which follow the `common` ones, of feature i.
MoreFields extraSetter(const std::vector<ExtraField>& extra, int common);

}  // namespace tinlod
