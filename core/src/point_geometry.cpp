// SPDX-License-Identifier: GPL-3.0-or-later
#include "point_geometry.h"

#include "tinlod/error.h"

namespace tinlod {
namespace {

bool isPointType(OGRwkbGeometryType type) {
  const OGRwkbGeometryType flat = wkbFlatten(type);
  return flat == wkbPoint || flat == wkbMultiPoint;
}

std::string typeName(OGRwkbGeometryType type) { return OGRGeometryTypeToName(wkbFlatten(type)); }

}  // namespace

void checkPointLayer(OGRLayer& layer, const std::string& what, const std::string& path) {
  const OGRwkbGeometryType type = layer.GetGeomType();
  if (type == wkbNone) throw Error(what + ": the layer of '" + path + "' has no geometry: a point layer is needed");
  if (wkbFlatten(type) != wkbUnknown && !isPointType(type))
    throw Error(what + ": the layer of '" + path + "' holds " + typeName(type) + " features: a point layer is needed");
}

void appendPoints(const OGRFeature& feature, const std::string& what, const std::string& path,
                  std::vector<std::array<double, 2>>& out) {
  const OGRGeometry* g = feature.GetGeometryRef();
  if (!g || g->IsEmpty()) return;
  if (!isPointType(g->getGeometryType()))
    throw Error(what + ": feature " + std::to_string(feature.GetFID()) + " of '" + path + "' is a " +
                typeName(g->getGeometryType()) + ", not a point");
  if (wkbFlatten(g->getGeometryType()) == wkbPoint) {
    out.push_back({g->toPoint()->getX(), g->toPoint()->getY()});
    return;
  }
  for (const OGRPoint* p : *g->toMultiPoint())
    if (!p->IsEmpty()) out.push_back({p->getX(), p->getY()});
}

}  // namespace tinlod
