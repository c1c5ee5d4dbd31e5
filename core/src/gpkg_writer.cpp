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
  return [&extra, common](OGRFeature& feature, std::size_t i) {
    for (std::size_t k = 0; k < extra.size(); ++k) {
      const double value = extra[k].values[i];
      const int field = common + static_cast<int>(k);
      if (!std::isfinite(value))
        feature.SetFieldNull(field);
      else if (extra[k].integer)
        feature.SetField(field, static_cast<int>(value));
      else
        feature.SetField(field, value);
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
  OGRLayer* vertices = out.createLayer("vertices", wkbPoint25D, tin.crsWkt, withExtra(vertexFields(), vertexExtra));
  OGRLayer* triangles = out.createLayer("triangles", wkbPolygon25D, tin.crsWkt, withExtra(triangleFields(), triangleExtra));
  out.begin();
  const double share = double(tin.vertices.size()) / (tin.vertices.size() + 2.0 * tin.triangles.size());
  writeVertices(tin, *vertices, extraSetter(vertexExtra, int(vertexFields().size())), progress.sub(0, 0.7 * share));
  writeTriangles(tin, tin.triangles, *triangles, extraSetter(triangleExtra, int(triangleFields().size())),
                 progress.sub(0.7 * share, 0.7));
  out.commit();
  out.finish(progress);
}

}  // namespace tinlod
