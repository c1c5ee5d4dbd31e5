// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/point_reader.h"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <memory>

#include "gdal_handles.h"
#include "text_and_paths.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

void addPoints(const OGRGeometry* g, std::vector<std::array<double, 2>>& out) {
  if (!g) return;
  switch (wkbFlatten(g->getGeometryType())) {
    case wkbPoint:
      out.push_back({g->toPoint()->getX(), g->toPoint()->getY()});
      break;
    case wkbMultiPoint:
      for (const OGRPoint* p : *g->toMultiPoint()) out.push_back({p->getX(), p->getY()});
      break;
    default:
      break;
  }
}

}  // namespace

void checkPointsExist(const std::string& path) {
  if (plainPathMissing(path)) throw Error("points to keep: '" + path + "' does not exist");
}

std::vector<std::array<double, 2>> readPoints(const std::string& path, const std::string& targetWkt,
                                              const ProgressRange& progress) {
  const DatasetPtr ds = openReadOnly(path, GDAL_OF_VECTOR);
  if (!ds || ds->GetLayerCount() < 1) throw Error("points to keep: '" + path + "' is not a vector file GDAL can read");
  OGRLayer* layer = ds->GetLayer(0);
  std::unique_ptr<OGRCoordinateTransformation> transform;
  OGRSpatialReference target;
  if (const OGRSpatialReference* src = layer->GetSpatialRef(); src && !targetWkt.empty() &&
                                                               target.importFromWkt(targetWkt.c_str()) == OGRERR_NONE) {
    OGRSpatialReference source(*src);
    source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    target.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    if (!source.IsSame(&target)) transform.reset(OGRCreateCoordinateTransformation(&source, &target));
  } else if (!layer->GetSpatialRef()) {
    progress.warn("points to keep: '" + path + "' has no CRS: taken to be in the TIN's CRS");
  }
  std::vector<std::array<double, 2>> points;
  for (auto& feature : *layer) addPoints(feature->GetGeometryRef(), points);
  for (auto& p : points)
    if (transform && !transform->Transform(1, &p[0], &p[1]))
      throw Error("points to keep: a point of '" + path + "' cannot be transformed to the TIN's CRS");
  if (points.empty())
    throw Error("points to keep: the first layer of '" + path + "' has no point features (a point layer is needed)");
  return points;
}

}  // namespace tinlod
