// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "tinlod/feedback.h"
#include "tinlod/output_files.h"
#include "tinlod/tin.h"

namespace tinlod {

struct GpkgWriteOptions {
  explicit GpkgWriteOptions(bool overwrite = false, std::map<std::string, std::string> metadata = {})
      : overwrite(overwrite), metadata(std::move(metadata)) {}
  // Replace tinlod's layers in an existing GeoPackage (its other layers are kept);
  // without it an existing file is an error.
  bool overwrite = false;
  // Stored as GeoPackage metadata (parameters, source) so a file explains itself.
  std::map<std::string, std::string> metadata;
  // More items known only once the rows are written (a check run alongside the writing):
  // asked for when the file is finished.
  std::function<std::map<std::string, std::string>()> lateMetadata;
  // writeTinGpkg: a spatial index on the vertices layer too (the triangles always have
  // one). Off by default, as for a hierarchy: nothing in tinlod reads vertices by place,
  // and on alps_2x2 the index is a third of the index writing.
  bool vertexIndex = false;
};

// Throws Error when `path` exists and overwrite is off, or its folder is missing. Returns
// the kind of tinlod output the existing file holds (its TINLOD_KIND), "" for none.
std::string checkOutputPath(const std::string& path, const GpkgWriteOptions& options);

// Warns when the run replaces another kind of tinlod TIN that `path` held (checkOutputPath's
// answer): a hierarchy by a sampled TIN loses its levels, groups and views. QGIS replaces
// without asking where the command line wants -overwrite.
void warnOfReplacedKind(const std::string& path, const std::string& held, const GpkgWriteOptions& options,
                        const ProgressRange& progress);

// A further field of the 'vertices' or 'triangles' layer: one value per feature, NaN and
// infinity written as null.
struct ExtraField {
  std::string name;
  std::vector<double> values;
  bool integer = false;
};

// Writes layers `vertices` (PointZ) and `triangles` (PolygonZ, one feature per
// triangle). In the file, ids count from 1 and equal the feature ids (fid), so
// v0, v1, v2 join to vertices.fid: vertex index i is written as id i + 1. Works on a temporary copy and renames it into place at the end, so a
// failed or cancelled run leaves `path` as it was.
void writeTinGpkg(const Tin& tin, const std::string& path, const GpkgWriteOptions& options,
                  const ProgressRange& progress, const std::vector<ExtraField>& vertexExtra = {},
                  const std::vector<ExtraField>& triangleExtra = {});
// The same into a file of a job's OutputFiles, moved into place with the job's other outputs.
void writeTinGpkg(const Tin& tin, const StagedFile& file, const GpkgWriteOptions& options,
                  const ProgressRange& progress, const std::vector<ExtraField>& vertexExtra = {},
                  const std::vector<ExtraField>& triangleExtra = {});

}  // namespace tinlod
