// SPDX-License-Identifier: GPL-3.0-or-later
#include "tin_gpkg_file.h"

#include <cmath>

namespace tinlod {
namespace {

std::vector<FieldSpec> withExtra(std::vector<FieldSpec> fields, const std::vector<ExtraField>& extra) {
  for (const ExtraField& f : extra) fields.push_back({f.name.c_str(), f.integer ? OFTInteger : OFTReal});
  return fields;
}

}  // namespace

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

TinGpkgFile::TinGpkgFile(const StagedFile& file, const GpkgWriteOptions& options, const std::string& crsWkt,
                         const std::vector<ExtraField>& vertexExtra, const std::vector<ExtraField>& triangleExtra)
    : out_(file, options, isTinlodLayer), vertexIndex_(options.vertexIndex) {
  const std::vector<FieldSpec> vfields = withExtra(vertexFields(), vertexExtra);
  const std::vector<FieldSpec> tfields = withExtra(triangleFields(), triangleExtra);
  vertexNames_ = fieldNames(vfields), triangleNames_ = fieldNames(tfields);  // the specs point into the callers' names
  out_.createLayer("vertices", wkbPoint25D, crsWkt, vfields, true);
  out_.createLayer("triangles", wkbPolygon25D, crsWkt, tfields, true);
  srsId_ = out_.srsId("vertices");
  vertexRows_.emplace(out_.database(), "vertices", vertexNames_);
}

void TinGpkgFile::clearVertexRows() {
  vertexRows_.reset();
  vertexRows_.emplace(out_.database(), "vertices", vertexNames_);  // sets GDAL's count triggers aside
  out_.database().execute("DELETE FROM vertices");
}

void TinGpkgFile::indexLater(const Tin& tin) {
  if (vertexIndex_) out_.indexLater("vertices", [&tin] { return vertexBoxes(tin); });
  out_.indexLater("triangles", [&tin] {
    return triangleBoxes(tin, tin.triangles.size(), [&tin](std::size_t i) -> const Triangle& { return tin.triangles[i]; });
  });
}

void TinGpkgFile::finish(const Tin& tin, const std::vector<ExtraField>& triangleExtra, const ProgressRange& rows,
                         const ProgressRange& rest) {
  const TriangleAt triangle = [&tin](std::size_t i) -> const Triangle& { return tin.triangles[i]; };
  GpkgFeatureRows triangleRows(out_.database(), "triangles", triangleNames_);
  writeTriangles(tin, tin.triangles.size(), triangle, triangleRows, out_.srsId("triangles"),
                 extraSetter(triangleExtra, int(triangleFields().size())), rows);
  out_.finish(rest);
}

GpkgFeatureRows& TinGpkgFile::triangleRows() {
  if (!triangleRows_) triangleRows_.emplace(out_.database(), "triangles", triangleNames_);
  return *triangleRows_;
}

void TinGpkgFile::finishRows(std::vector<RtreeBox> vertexBoxes, std::vector<RtreeBox> triangleBoxes,
                             const ProgressRange& progress) {
  vertexRows_->finish();
  triangleRows().finish();
  if (vertexIndex_) out_.indexLater("vertices", [boxes = std::move(vertexBoxes)]() mutable { return std::move(boxes); });
  out_.indexLater("triangles", [boxes = std::move(triangleBoxes)]() mutable { return std::move(boxes); });
  out_.finish(progress);
}

}  // namespace tinlod
