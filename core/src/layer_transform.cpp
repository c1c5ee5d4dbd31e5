// SPDX-License-Identifier: GPL-3.0-or-later
#include "layer_transform.h"

#include "layer_crs.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

std::unique_ptr<OGRCoordinateTransformation> transformBetween(const OGRSpatialReference& src, const std::string& targetWkt,
                                                              const std::string& what, const std::string& fix,
                                                              const ProgressRange& progress) {
  OGRSpatialReference target;
  if (targetWkt.empty()) {
    progress.warn(what + ": the TIN has no CRS: the coordinates are used as they are");
    return nullptr;
  }
  if (target.importFromWkt(targetWkt.c_str()) != OGRERR_NONE) throw Error(what + ": the TIN's CRS cannot be read");
  OGRSpatialReference source(src);
  // x = easting or longitude, as the TIN's coordinates are stored.
  source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  target.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (source.IsSame(&target)) return nullptr;
  std::unique_ptr<OGRCoordinateTransformation> transform(OGRCreateCoordinateTransformation(&source, &target));
  if (!transform)
    throw Error(what + ": no transformation from " + (source.GetName() ? source.GetName() : std::string("its CRS")) + " to " +
                (target.GetName() ? target.GetName() : std::string("the TIN's CRS")) + ": " + fix);
  return transform;
}

OGRSpatialReference srsFromText(const std::string& srs, const std::string& what) {
  OGRSpatialReference out;
  if (out.SetFromUserInput(srs.c_str()) != OGRERR_NONE)
    throw Error(what + ": '" + srs + "' is not a CRS GDAL understands: use e.g. EPSG:4326");
  return out;
}

}  // namespace

std::unique_ptr<OGRCoordinateTransformation> transformToTin(OGRLayer& layer, const std::string& targetWkt,
                                                            const std::string& what, const ProgressRange& progress) {
  const OGRSpatialReference* src = layerCrs(layer);
  if (!src) {
    progress.warn(what + ": the layer has no CRS: taken to be in the TIN's CRS");
    return nullptr;
  }
  return transformBetween(*src, targetWkt, what, "reproject the layer to the TIN's CRS first", progress);
}

void checkSrsText(const std::string& srs, const std::string& what) { srsFromText(srs, what); }

std::unique_ptr<OGRCoordinateTransformation> transformToTin(const std::string& srs, const std::string& targetWkt,
                                                            const std::string& what, const ProgressRange& progress) {
  return transformBetween(srsFromText(srs, what), targetWkt, what, "give the coordinates in the TIN's CRS", progress);
}

}  // namespace tinlod
