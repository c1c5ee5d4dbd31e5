// SPDX-License-Identifier: GPL-3.0-or-later
#include "layer_transform.h"

namespace tinlod {

std::unique_ptr<OGRCoordinateTransformation> transformToTin(OGRLayer& layer, const std::string& targetWkt,
                                                            const std::string& what, const ProgressRange& progress) {
  const OGRSpatialReference* src = layer.GetSpatialRef();
  if (!src) {
    progress.warn(what + ": the layer has no CRS: taken to be in the TIN's CRS");
    return nullptr;
  }
  OGRSpatialReference target;
  if (targetWkt.empty() || target.importFromWkt(targetWkt.c_str()) != OGRERR_NONE) return nullptr;
  OGRSpatialReference source(*src);
  // x = easting or longitude, as the TIN's coordinates are stored.
  source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  target.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (source.IsSame(&target)) return nullptr;
  return std::unique_ptr<OGRCoordinateTransformation>(OGRCreateCoordinateTransformation(&source, &target));
}

}  // namespace tinlod
