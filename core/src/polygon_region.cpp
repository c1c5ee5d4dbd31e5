// SPDX-License-Identifier: GPL-3.0-or-later
#include "polygon_region.h"

#include <geos_c.h>
#include <ogrsf_frmts.h>

#include <algorithm>

#include "gdal_handles.h"
#include "layer_source.h"
#include "layer_transform.h"
#include "text_and_paths.h"
#include "tinlod/error.h"

namespace tinlod {

struct PolygonRegion::Impl {
  GEOSContextHandle_t context = GEOS_init_r();
  GEOSGeometry* area = nullptr;
  const GEOSPreparedGeometry* prepared = nullptr;
  std::array<double, 4> envelope{};  // xmin, ymin, xmax, ymax
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
  const OpenLayer open = openLayer(path, what);
  OGRLayer& layer = *open.layer;
  const auto transform = transformToTin(layer, targetWkt, what + " ('" + path + "')", progress);
  const OGRGeometryCollection polygons = polygonsOf(layer, transform.get(), what);
  if (polygons.IsEmpty()) {
    const bool polygonLayer = OGR_GT_IsSubClassOf(wkbFlatten(layer.GetGeomType()), wkbCurvePolygon) ||
                              OGR_GT_IsSubClassOf(wkbFlatten(layer.GetGeomType()), wkbMultiSurface);
    throw Error(what + ": the first layer of '" + path + "' has no polygons" +
                (polygonLayer ? " (its polygon layer '" + std::string(layer.GetName()) + "' is empty)" : " (a polygon layer is needed)"));
  }
  GEOSGeometry* collection = polygons.exportToGEOS(impl_->context);
  if (!collection) throw Error(what + ": the polygons of '" + path + "' are not valid geometries");
  // Overlapping polygons become one area; invalid rings are mended rather than refused.
  GEOSGeometry* valid = GEOSMakeValid_r(impl_->context, collection);
  GEOSGeom_destroy_r(impl_->context, collection);
  impl_->area = valid ? GEOSUnaryUnion_r(impl_->context, valid) : nullptr;
  if (valid) GEOSGeom_destroy_r(impl_->context, valid);
  if (!impl_->area) throw Error(what + ": the polygons of '" + path + "' cannot be joined into one area");
  impl_->prepared = GEOSPrepare_r(impl_->context, impl_->area);
  if (!impl_->prepared) throw Error(what + ": the polygons of '" + path + "' cannot be prepared for testing");
  OGREnvelope e;
  polygons.getEnvelope(&e);
  impl_->envelope = {e.MinX, e.MinY, e.MaxX, e.MaxY};
}

PolygonRegion::~PolygonRegion() = default;

const std::array<double, 4>& PolygonRegion::envelope() const { return impl_->envelope; }

bool PolygonRegion::meets(const std::array<std::array<double, 2>, 3>& t) const {
  // Most triangles are far from the region: its envelope rejects them without GEOS.
  const double x0 = std::min({t[0][0], t[1][0], t[2][0]}), x1 = std::max({t[0][0], t[1][0], t[2][0]});
  const double y0 = std::min({t[0][1], t[1][1], t[2][1]}), y1 = std::max({t[0][1], t[1][1], t[2][1]});
  if (x1 < impl_->envelope[0] || x0 > impl_->envelope[2] || y1 < impl_->envelope[1] || y0 > impl_->envelope[3]) return false;
  GEOSContextHandle_t c = impl_->context;
  GEOSCoordSequence* ring = GEOSCoordSeq_create_r(c, 4, 2);
  for (unsigned k = 0; k < 4; ++k) GEOSCoordSeq_setXY_r(c, ring, k, t[k % 3][0], t[k % 3][1]);
  GEOSGeometry* triangle = GEOSGeom_createPolygon_r(c, GEOSGeom_createLinearRing_r(c, ring), nullptr, 0);
  const char meets = GEOSPreparedIntersects_r(c, impl_->prepared, triangle);
  GEOSGeom_destroy_r(c, triangle);
  return meets == 1;
}

}  // namespace tinlod
