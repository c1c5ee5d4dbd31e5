// SPDX-License-Identifier: GPL-3.0-or-later
#include "layer_crs.h"

#include <cpl_conv.h>

#include <cstring>

namespace tinlod {

const OGRSpatialReference* layerCrs(OGRLayer& layer) {
  const OGRSpatialReference* srs = layer.GetSpatialRef();
  const char* name = srs ? srs->GetName() : nullptr;
  if (name && (std::strcmp(name, "Undefined geographic SRS") == 0 || std::strcmp(name, "Undefined Cartesian SRS") == 0) &&
      std::strcmp(layer.GetDataset() ? layer.GetDataset()->GetDriverName() : "", "GPKG") == 0)
    return nullptr;
  return srs;
}

std::string crsLabel(const OGRSpatialReference& srs) {
  const char* name = srs.GetName();
  if (name && *name && std::strcmp(name, "unknown") != 0) return name;
  char* proj4 = nullptr;
  std::string label = "an unnamed CRS";
  if (srs.exportToProj4(&proj4) == OGRERR_NONE && proj4 && *proj4) label = std::string("'") + proj4 + "'";
  CPLFree(proj4);
  return label;
}

}  // namespace tinlod
