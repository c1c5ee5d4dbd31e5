// SPDX-License-Identifier: GPL-3.0-or-later
// Private: owning GDAL datasets, and the WKT tinlod writes, for the core's I/O files.
#pragma once

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <memory>
#include <string>

namespace tinlod {

struct GdalCloser {
  void operator()(GDALDataset* ds) const { GDALClose(ds); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, GdalCloser>;

// Opens `path` read-only with GDALOpenEx's `flags` (GDAL_OF_RASTER, GDAL_OF_VECTOR) and,
// when given, only the listed drivers. GDAL's own messages are kept quiet: the caller
// says what went wrong in the user's terms. Null when GDAL cannot open it.
DatasetPtr openReadOnly(const std::string& path, unsigned flags, const char* const* drivers = nullptr);

// The names of a dataset's layers, "a, b" ("none" without any), for messages that say
// which layers a file has when the one asked for is not there.
std::string layerNames(GDALDataset& ds);

// WKT2 (2019), the form tinlod stores and compares CRSs in.
std::string wkt2(const OGRSpatialReference& srs);

}  // namespace tinlod
