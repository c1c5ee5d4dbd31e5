// SPDX-License-Identifier: GPL-3.0-or-later
#include "layer_crs.h"

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

}  // namespace tinlod
