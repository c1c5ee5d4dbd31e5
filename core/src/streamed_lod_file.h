// SPDX-License-Identifier: GPL-3.0-or-later
// Private: tinlod lod's GeoPackage of a catalogue, written a tile at a time, so that the
// output is never held whole: its rows as each tile's part comes, its spatial indexes
// from the boxes kept meanwhile (16 bytes a triangle).
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "catalogue_lod.h"
#include "gpkg_geometry_blob.h"
#include "packed_rtree.h"
#include "tin_gpkg_file.h"
#include "tinlod/gpkg_writer.h"
#include "tinlod/output_files.h"

namespace tinlod {

class StreamedLodFile : public CatalogueLodSink {
 public:
  // The layers are made when the tiles' CRS is known (start); `options.metadata` gets TINLOD_CRS,
  // and TINLOD_OUTLINE_VERTICES once setOutline has counted them.
  StreamedLodFile(const StagedFile& file, GpkgWriteOptions options);

  void start(const std::string& crsWkt, const std::string& crsName) override;
  void add(const LodPiece& piece, const ProgressRange& progress) override;
  void setOutline(const std::vector<VertexId>& sharedOutline, std::size_t outlineVertices) override;
  // The indexes and the commit, after the last piece.
  void finish(const ProgressRange& progress);

  std::size_t vertices() const { return vertices_; }
  std::size_t triangles() const { return triangles_; }
  // Triangles by their first level.
  const std::vector<std::size_t>& trianglesByFirstLevel() const { return byFirstLevel_; }
  const Envelope& extent() const { return extent_; }  // of the vertices
  const std::string& crsName() const { return crsName_; }

 private:
  const StagedFile& stagedFile_;
  GpkgWriteOptions options_;
  std::unique_ptr<TinGpkgFile> file_;
  std::vector<RtreeBox> vertexBoxes_, triangleBoxes_;
  std::size_t vertices_ = 0, triangles_ = 0, outlineVertices_ = 0;
  std::vector<std::size_t> byFirstLevel_;
  Envelope extent_ = Envelope::empty();
  std::string crsName_;
};

}  // namespace tinlod
