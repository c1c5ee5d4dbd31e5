// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/gpkg_writer.h"

#include <string>

#include "tin_gpkg_file.h"
#include "tin_outline.h"

namespace tinlod {

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
  // The vertices' `outline` column is the sampler's (cells on the valid area's outline);
  // info counts the TIN's own outline from this, as a hierarchy's levels table does.
  GpkgWriteOptions withOutline = options;
  withOutline.metadata["TINLOD_OUTLINE_VERTICES"] = std::to_string(countOutlineVertices(tin));
  TinGpkgFile out(file, withOutline, tin.crsWkt, vertexExtra, triangleExtra);
  out.indexLater(tin);
  const double rows = 0.8, share = double(tin.vertices.size()) / (tin.vertices.size() + 2.0 * tin.triangles.size());
  writeVertices(tin, out.vertexRows(), out.srsId(), extraSetter(vertexExtra, int(vertexFields().size())),
                progress.sub(0, rows * share));
  out.finish(tin, triangleExtra, progress.sub(rows * share, rows), progress.sub(rows, 1));
}

}  // namespace tinlod
