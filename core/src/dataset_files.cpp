// SPDX-License-Identifier: GPL-3.0-or-later
#include "dataset_files.h"

#include <gdal_priv.h>

namespace tinlod {

namespace {

// "contours.gpkg|layername=c" as QGIS names a layer: the file is what may not be replaced.
std::string fileOf(const std::string& spec) {
  const std::size_t bar = spec.find('|');
  return bar == std::string::npos ? spec : spec.substr(0, bar);
}

}  // namespace

std::vector<std::string> datasetFiles(const std::string& spec) {
  const std::string path = fileOf(spec);
  std::vector<std::string> files{path};
  if (path.empty()) return files;
  GDALAllRegister();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  GDALDataset* ds = GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_VECTOR | GDAL_OF_READONLY);
  CPLPopErrorHandler();
  if (!ds) return files;
  char** list = ds->GetFileList();
  for (char** f = list; f && *f; ++f) files.emplace_back(*f);
  CSLDestroy(list);
  GDALClose(ds);
  return files;
}

std::vector<std::string> datasetFiles(const std::vector<std::string>& paths) {
  std::vector<std::string> files;
  for (const std::string& p : paths) {
    const std::vector<std::string> more = datasetFiles(p);
    files.insert(files.end(), more.begin(), more.end());
  }
  return files;
}

}  // namespace tinlod
