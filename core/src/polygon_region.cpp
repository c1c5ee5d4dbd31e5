// SPDX-License-Identifier: GPL-3.0-or-later
#include "polygon_region.h"

#include <geos_c.h>
#include <ogrsf_frmts.h>

#include "gdal_handles.h"
#include "layer_transform.h"
#include "text_and_paths.h"
#include "tinlod/error.h"

namespace tinlod {

struct PolygonRegion::Impl {
  GEOSContextHandle_t context = GEOS_init_r();
  GEOSGeometry* area = nullptr;
  const GEOSPreparedGeometry* prepared = nullptr;
  ~Impl() {
    if (prepared) GEOSPreparedGeom_destroy_r(context, prepared);
    if (area) GEOSGeom_destroy_r(context, area);
    GEOS_finish_r(context);
  }
};

namespace {

// Every polygon of the layer, transformed, in one collection.
OGRGeometryCollection polygonsOf(OGRLayer& layer, OGRCoordinateTransformation* transform, const std::string& what) {
  OGRGeometryCollection all;
  for (auto& feature : layer) {
    const OGRGeometry* g = feature->GetGeometryRef();
    if (!g || (wkbFlatten(g->getGeometryType()) != wkbPolygon && wkbFlatten(g->getGeometryType()) != wkbMultiPolygon)) continue;
    OGRGeometry* copy = g->clone();
    if (transform && copy->transform(transform) != OGRERR_NONE) {
      delete copy;
      throw Error(what + ": a polygon cannot be transformed to the TIN's CRS");
    }
    all.addGeometryDirectly(copy);
  }
  return all;
}

}  // namespace

PolygonRegion::PolygonRegion(const std::string& path, const std::string& targetWkt, const std::string& what,
                             const ProgressRange& progress)
    : impl_(std::make_unique<Impl>()) {
  if (plainPathMissing(path)) throw Error(what + ": '" + path + "' does not exist");
  const DatasetPtr ds = openReadOnly(path, GDAL_OF_VECTOR);
  if (!ds || ds->GetLayerCount() < 1) throw Error(what + ": '" + path + "' is not a vector file GDAL can read");
  OGRLayer& layer = *ds->GetLayer(0);
  const auto transform = transformToTin(layer, targetWkt, what + " ('" + path + "')", progress);
  const OGRGeometryCollection polygons = polygonsOf(layer, transform.get(), what);
  if (polygons.IsEmpty()) throw Error(what + ": the first layer of '" + path + "' has no polygons (a polygon layer is needed)");
  GEOSGeometry* collection = polygons.exportToGEOS(impl_->context);
  if (!collection) throw Error(what + ": the polygons of '" + path + "' are not valid geometries");
  // Overlapping polygons become one area; invalid rings are mended rather than refused.
  GEOSGeometry* valid = GEOSMakeValid_r(impl_->context, collection);
  GEOSGeom_destroy_r(impl_->context, collection);
  impl_->area = valid ? GEOSUnaryUnion_r(impl_->context, valid) : nullptr;
  if (valid) GEOSGeom_destroy_r(impl_->context, valid);
  if (!impl_->area) throw Error(what + ": the polygons of '" + path + "' cannot be joined into one area");
  impl_->prepared = GEOSPrepare_r(impl_->context, impl_->area);
}

PolygonRegion::~PolygonRegion() = default;

bool PolygonRegion::contains(double x, double y) const {
  GEOSGeometry* point = GEOSGeom_createPointFromXY_r(impl_->context, x, y);
  const char inside = GEOSPreparedIntersects_r(impl_->context, impl_->prepared, point);
  GEOSGeom_destroy_r(impl_->context, point);
  return inside == 1;
}

}  // namespace tinlod
