// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/point_reader.h"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <memory>

#include "gdal_handles.h"
#include "layer_source.h"
#include "layer_transform.h"
#include "point_geometry.h"
#include "text_and_paths.h"
#include "tinlod/error.h"

namespace tinlod {
void checkPointsExist(const std::string& path, const std::string& what) {
  if (plainPathMissing(parseLayerSource(path, what).path)) throw Error(what + ": '" + path + "' does not exist");
  // A layer of polygons would otherwise be refused only after the long work (in every
  // tile of a tiled run, after a survey pass).
  const OpenLayer open = openLayer(path, what);
  checkPointLayer(*open.layer, what, open.path);
}

std::vector<std::array<double, 2>> readPoints(const std::string& path, const std::string& targetWkt,
                                              const ProgressRange& progress, const std::string& what) {
  const OpenLayer open = openLayer(path, what);
  OGRLayer* layer = open.layer;
  const auto transform = transformToTin(*layer, targetWkt, what + " ('" + path + "')", progress);
  checkPointLayer(*layer, what, open.path);
  std::vector<std::array<double, 2>> points;
  for (auto& feature : *layer) appendPoints(*feature, what, open.path, points);
  for (auto& p : points)
    if (transform && !transform->Transform(1, &p[0], &p[1]))
      throw Error(what + ": a point of '" + path + "' cannot be transformed to the TIN's CRS");
  if (points.empty())
    throw Error(what + ": the layer of '" + path + "' has no point features (a point layer is needed)");
  return points;
}

}  // namespace tinlod
