// SPDX-License-Identifier: GPL-3.0-or-later
// Private: a GeoPackage being written for one tinlod job. GDAL stays in the I/O files.
#pragma once

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <string>
#include <vector>

#include "packed_rtree.h"
#include "sqlite_database.h"
#include "tinlod/feedback.h"
#include "tinlod/gpkg_writer.h"
#include "tinlod/output_files.h"

namespace tinlod {

struct FieldSpec {
  const char* name;
  OGRFieldType type = OFTInteger;
  OGRFieldSubType subType = OFSTNone;
};

// Works on the staged copy of the output (or a new GeoPackage): the job's own layers and
// views, those for which `ours` is true, are dropped first, the rest is kept. GDAL makes
// the layers and writes the small ones; database() then hands the file to SQLite for the
// big ones, whose rows and spatial indexes are written in bulk. finish() closes it; the
// job's OutputFiles moves it into place.
class GpkgOutput {
 public:
  GpkgOutput(const StagedFile& file, const GpkgWriteOptions& options, std::function<bool(const std::string&)> ours);
  ~GpkgOutput();
  GpkgOutput(const GpkgOutput&) = delete;
  GpkgOutput& operator=(const GpkgOutput&) = delete;

  // A bulk layer is made empty and without a spatial index: its rows are written through
  // database() and its index by indexLater().
  OGRLayer* createLayer(const char* name, OGRwkbGeometryType type, const std::string& crsWkt,
                        const std::vector<FieldSpec>& fields, bool bulk = false);
  // Ends GDAL's part (metadata written, file closed) on the first call and opens the file
  // in SQLite, in one transaction that finish() commits.
  SqliteDatabase& database();
  // The GeoPackage srs_id of a layer made by createLayer, for its geometry blobs.
  std::int32_t srsId(const std::string& table);
  // Packs the R-tree of bulk layer `table` from its features' boxes in the background
  // (one layer after another, while the caller writes rows); finish() stores it.
  void indexLater(const std::string& table, std::function<std::vector<RtreeBox>()> boxes);
  void execute(const std::string& sql);
  // A GeoPackage view registered as a feature layer with the geometry of `baseTable`, so
  // that GDAL and QGIS list it beside the tables; made in the bulk writer's transaction.
  void createFeatureView(const std::string& name, const std::string& select, const std::string& baseTable,
                         const std::string& description);
  void begin();
  void commit();
  // Spatial indexes, the late metadata and the final commit, over `progress`.
  void finish(const ProgressRange& progress);

 private:
  struct PendingIndex {
    std::string table;
    // Shared so that the next packing can wait for it; held by pointer so that writing can
    // take it and free it table by table.
    std::shared_future<std::shared_ptr<PackedRtree>> tree;
  };
  void dropOurs(const std::function<bool(const std::string&)>& ours);
  // True when every layer and metadata item of the file is the job's own.
  static bool holdsOnly(const std::filesystem::path& path, const std::function<bool(const std::string&)>& ours);
  void writeMetadata(bool withLate);
  void closeGdal();
  // What dropping the job's old layers left free is given back (GDAL's part only: the
  // bulk writer compacts in its own connection).
  void compactIfDropped();
  void finishDatabase(const ProgressRange& progress);
  std::vector<PendingIndex> indexes_;
  // Set when the output is given up: the packings still running stop (their futures'
  // destructors would wait for them).
  std::shared_ptr<std::atomic<bool>> abandonIndexes_ = std::make_shared<std::atomic<bool>>(false);
  std::vector<std::string> withoutCrs_;  // bulk layers made without a CRS
  std::unique_ptr<SqliteDatabase> db_;
  bool vacuum_ = false;
  std::string said(const std::string& gdalMessage) const { return writeFailureInUserTerms(file_, gdalMessage); }
  StagedFile file_;
  GpkgWriteOptions options_;
  GDALDataset* ds_ = nullptr;
};

void writeFeature(OGRLayer& layer, OGRFeature& feature);

// Every layer tinlod writes, whichever command wrote the file: replacing a file's TIN or
// hierarchy drops all of them, so no view is left pointing at replaced triangles.
bool isTinlodLayer(const std::string& name);

}  // namespace tinlod
