// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/gpkg_writer.h"

#include <cmath>

#include "gpkg_output.h"
#include "tin_layers.h"

namespace tinlod {
namespace {

std::vector<FieldSpec> withExtra(std::vector<FieldSpec> fields, const std::vector<ExtraField>& extra) {
  for (const ExtraField& f : extra) fields.push_back({f.name.c_str(), f.integer ? OFTInteger : OFTReal});
  return fields;
}

// Sets the extra fields, which follow the `common` ones, of feature i.
MoreFields extraSetter(const std::vector<ExtraField>& extra, int common) {
  if (extra.empty()) return {};
  return [&extra, common](GpkgFeatureRows& rows, std::size_t i) {
    for (std::size_t k = 0; k < extra.size(); ++k) {
      const double value = extra[k].values[i];
      const int field = common + static_cast<int>(k);
      if (!std::isfinite(value))
        rows.setNull(field);
      else if (extra[k].integer)
        rows.set(field, static_cast<std::int64_t>(value));
      else
        rows.setReal(field, value);
    }
  };
}

}  // namespace

void writeTinGpkg(const Tin& tin, const std::string& path, const GpkgWriteOptions& options,
                  const ProgressRange& progress, const std::vector<ExtraField>& vertexExtra,
                  const std::vector<ExtraField>& triangleExtra) {
  checkOutputPath(path, options);
  OutputFiles files(options.overwrite);
  writeTinGpkg(tin, files.add(path, "output", true), options, progress, vertexExtra, triangleExtra);
  files.commit();
}

void writeTinGpkg(const Tin& tin, const StagedFile& file, const GpkgWriteOptions& options,
                  const ProgressRange& progress, const std::vector<ExtraField>& vertexExtra,
                  const std::vector<ExtraField>& triangleExtra) {
  GpkgOutput out(file, options, isTinlodLayer);
  const std::vector<FieldSpec> vfields = withExtra(vertexFields(), vertexExtra);
  const std::vector<FieldSpec> tfields = withExtra(triangleFields(), triangleExtra);
  out.createLayer("vertices", wkbPoint25D, tin.crsWkt, vfields, true);
  out.createLayer("triangles", wkbPolygon25D, tin.crsWkt, tfields, true);
  SqliteDatabase& db = out.database();
  if (options.vertexIndex) out.indexLater("vertices", [&tin] { return vertexBoxes(tin); });
  const TriangleAt triangle = [&tin](std::size_t i) -> const Triangle& { return tin.triangles[i]; };
  out.indexLater("triangles", [&tin, triangle] { return triangleBoxes(tin, tin.triangles.size(), triangle); });
  const double rows = 0.8, share = double(tin.vertices.size()) / (tin.vertices.size() + 2.0 * tin.triangles.size());
  GpkgFeatureRows vertexRows(db, "vertices", fieldNames(vfields));
  writeVertices(tin, vertexRows, out.srsId("vertices"), extraSetter(vertexExtra, int(vertexFields().size())),
                progress.sub(0, rows * share));
  GpkgFeatureRows triangleRows(db, "triangles", fieldNames(tfields));
  writeTriangles(tin, tin.triangles.size(), triangle, triangleRows, out.srsId("triangles"),
                 extraSetter(triangleExtra, int(triangleFields().size())), progress.sub(rows * share, rows));
  out.finish(progress.sub(rows, 1));
}

}  // namespace tinlod
