// SPDX-License-Identifier: GPL-3.0-or-later
// Private: a GeoPackage being written for one tinlod job. GDAL stays in the I/O files.
#pragma once

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

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
// views, those for which `ours` is true, are dropped first, the rest is kept. finish()
// closes it; the job's OutputFiles moves it into place.
class GpkgOutput {
 public:
  GpkgOutput(const StagedFile& file, const GpkgWriteOptions& options, std::function<bool(const std::string&)> ours);
  ~GpkgOutput();
  GpkgOutput(const GpkgOutput&) = delete;
  GpkgOutput& operator=(const GpkgOutput&) = delete;

  OGRLayer* createLayer(const char* name, OGRwkbGeometryType type, const std::string& crsWkt,
                        const std::vector<FieldSpec>& fields);
  void execute(const std::string& sql);
  // Run once the features are written and the file closed. GDAL 3.6 builds R-trees in a
  // background thread with a database attached, and SQL run meanwhile fails with
  // "database is locked"; the file is reopened for these statements instead.
  void executeAfterClose(const std::string& sql) { deferred_.push_back(sql); }
  // A GeoPackage view registered as a feature layer with the geometry of `baseTable`, so
  // that GDAL and QGIS list it beside the tables (created after close).
  void createFeatureView(const std::string& name, const std::string& select, const std::string& baseTable,
                         const std::string& description);
  void begin();
  void commit();
  // The last 30 % of `progress`: GDAL builds spatial indexes while closing.
  void finish(const ProgressRange& progress);

 private:
  void dropOurs(const std::function<bool(const std::string&)>& ours);
  void runDeferred();
  std::vector<std::string> deferred_;
  bool vacuum_ = false;
  std::string said(const std::string& gdalMessage) const { return inUserTerms(file_, gdalMessage); }
  StagedFile file_;
  GpkgWriteOptions options_;
  GDALDataset* ds_ = nullptr;
};

void writeFeature(OGRLayer& layer, OGRFeature& feature);

// Every layer tinlod writes, whichever command wrote the file: replacing a file's TIN or
// hierarchy drops all of them, so no view is left pointing at replaced triangles.
bool isTinlodLayer(const std::string& name);

}  // namespace tinlod
