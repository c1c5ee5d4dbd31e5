// SPDX-License-Identifier: GPL-3.0-or-later
// Private: a vector layer named as QGIS names it, "file.gpkg|layername=wells".
#pragma once

#include <ogrsf_frmts.h>

#include <string>

#include "gdal_handles.h"

namespace tinlod {

struct LayerSource {
  std::string path;
  std::string layer;   // by name, when given
  int layerIndex = 0;  // else by position: the first unless "|layerid=N"
};

// Splits "path|layername=name" (or "|layerid=N"); a plain path is the file's first layer.
// Throws Error for a subset filter or another option: the core would read the whole layer.
LayerSource parseLayerSource(const std::string& spec, const std::string& what);

// The file of `spec` opened read-only, and its layer. Throws Error naming `what` when the
// file is missing, not a vector file, or without that layer.
struct OpenLayer {
  DatasetPtr dataset;
  OGRLayer* layer = nullptr;
  std::string path;
};
OpenLayer openLayer(const std::string& spec, const std::string& what);

}  // namespace tinlod
