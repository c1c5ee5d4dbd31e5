// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/gpkg_writer.h"

#include <cmath>

#include "gpkg_output.h"
#include "tin_layers.h"

namespace tinlod {

void writeTinGpkg(const Tin& tin, const std::string& path, const GpkgWriteOptions& options,
                  const ProgressRange& progress, const std::vector<VertexField>& extra) {
  GpkgOutput out(path, options, isTinlodLayer);
  std::vector<FieldSpec> fields = vertexFields();
  const int common = static_cast<int>(fields.size());
  for (const VertexField& f : extra) fields.push_back({f.name.c_str(), f.integer ? OFTInteger : OFTReal});
  OGRLayer* vertices = out.createLayer("vertices", wkbPoint25D, tin.crsWkt, fields);
  OGRLayer* triangles = out.createLayer("triangles", wkbPolygon25D, tin.crsWkt, triangleFields());
  out.begin();
  const double share = double(tin.vertices.size()) / (tin.vertices.size() + 2.0 * tin.triangles.size());
  const MoreFields more = [&](OGRFeature& feature, std::size_t i) {
    for (std::size_t k = 0; k < extra.size(); ++k) {
      const double value = extra[k].values[i];
      if (!std::isfinite(value))
        feature.SetFieldNull(common + static_cast<int>(k));
      else if (extra[k].integer)
        feature.SetField(common + static_cast<int>(k), static_cast<int>(value));
      else
        feature.SetField(common + static_cast<int>(k), value);
    }
  };
  writeVertices(tin, *vertices, extra.empty() ? MoreFields() : more, progress.sub(0, 0.7 * share));
  writeTriangles(tin, tin.triangles, *triangles, {}, progress.sub(0.7 * share, 0.7));
  out.commit();
  out.finish(progress);
}

}  // namespace tinlod
