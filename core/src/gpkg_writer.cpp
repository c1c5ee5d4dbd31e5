// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/gpkg_writer.h"

#include "gpkg_output.h"
#include "tin_layers.h"

namespace tinlod {

void writeTinGpkg(const Tin& tin, const std::string& path, const GpkgWriteOptions& options,
                  const ProgressRange& progress) {
  GpkgOutput out(path, options, isTinlodLayer);
  OGRLayer* vertices = out.createLayer("vertices", wkbPoint25D, tin.crsWkt, vertexFields());
  OGRLayer* triangles = out.createLayer("triangles", wkbPolygon25D, tin.crsWkt, triangleFields());
  out.begin();
  const double share = double(tin.vertices.size()) / (tin.vertices.size() + 2.0 * tin.triangles.size());
  writeVertices(tin, *vertices, {}, progress.sub(0, 0.7 * share));
  writeTriangles(tin, tin.triangles, *triangles, {}, progress.sub(0.7 * share, 0.7));
  out.commit();
  out.finish(progress);
}

}  // namespace tinlod
