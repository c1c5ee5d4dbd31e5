// SPDX-License-Identifier: GPL-3.0-or-later
#include "gdal_handles.h"

#include <ogrsf_frmts.h>

namespace tinlod {

DatasetPtr openReadOnly(const std::string& path, unsigned flags, const char* const* drivers) {
  GDALAllRegister();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  DatasetPtr ds(static_cast<GDALDataset*>(GDALOpenEx(path.c_str(), flags | GDAL_OF_READONLY, drivers, nullptr, nullptr)));
  CPLPopErrorHandler();
  return ds;
}

std::string layerNames(GDALDataset& ds) {
  std::string names;
  for (int i = 0; i < ds.GetLayerCount(); ++i) names += (i ? ", " : "") + std::string(ds.GetLayer(i)->GetName());
  return names.empty() ? "none" : names;
}

std::string wkt2(const OGRSpatialReference& srs) {
  char* wkt = nullptr;
  const char* options[] = {"FORMAT=WKT2_2019", nullptr};
  srs.exportToWkt(&wkt, options);
  std::string out = wkt ? wkt : "";
  CPLFree(wkt);
  return out;
}

}  // namespace tinlod
