// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/hierarchy_reader.h"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "layer_crs.h"
#include "gdal_handles.h"
#include "stored_hierarchy.h"
#include "tinlod/error.h"
#include "tinlod/importance.h"

namespace tinlod {
namespace {

std::string wktOf(OGRLayer& layer) {
  const OGRSpatialReference* srs = layerCrs(layer);
  return srs ? wkt2(*srs) : "";
}

std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

// A number of the file's metadata: the whole text, whatever the C locale (QGIS may set
// one with a decimal comma); atof would read "5x" as 5 and "nan" as a number.
bool parsedNumber(const std::string& text, double& value) {
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  return error == std::errc() && stop == end && std::isfinite(value);
}

// A percentage of the file's metadata, up to 100 or below it; 0 when the file has none
// (older files, or "none (threshold mode)" from a build with a threshold).
double storedPercentage(const HierarchyInfo& info, const char* key, bool hundredAllowed) {
  const auto item = info.metadata.find(key);
  if (item == info.metadata.end() || item->second.empty() || item->second.rfind("none", 0) == 0) return 0;
  double value = 0;
  if (!parsedNumber(item->second, value) || value < 0 || value > 100 || (value == 100 && !hundredAllowed))
    throwDamaged(info.path, "its TINLOD_" + upper(key) + " is '" + item->second + "', not a percentage from 0 to " +
                                (hundredAllowed ? "100" : "less than 100"));
  return value;
}

void readOptions(const HierarchyInfo& info, Hierarchy& h) {
  auto item = [&](const char* key) { auto it = info.metadata.find(key); return it == info.metadata.end() ? std::string() : it->second; };
  if (info.kind != "hierarchy") {
    h.tinMethod = item("method").empty() ? "sample" : item("method");
    return;
  }
  const std::string method = item("method");
  if (!method.empty()) {
    try {
      h.options.measure = parseMeasure(method);
    } catch (const Error&) {
      throwDamaged(info.path, "its TINLOD_METHOD is '" + method + "', not a method tinlod knows");
    }
  }
  h.options.deletePct = storedPercentage(info, "delete_pct", true);
  h.options.stopPct = storedPercentage(info, "stop_pct", false);
}

OGRLayer& requiredLayer(GDALDataset& ds, const std::string& path, const char* name, bool hierarchy) {
  OGRLayer* layer = ds.GetLayerByName(name);
  if (layer) return *layer;
  if (hierarchy)
    throwDamaged(path, std::string("it is a hierarchy (TINLOD_KIND) but has no ") + name +
                           " table; build it again with tinlod build");
  throw Error("'" + path + "' has no " + name + " table: it is not a tinlod TIN");
}

// A single TIN's one level has what was read, not what the file says it has.
void countSingleLevel(Hierarchy& h) {
  h.levels.at(0).vertices = h.base.vertices.size();
  h.levels.at(0).triangles = h.triangles.size();
}

}  // namespace

StoredHierarchy readHierarchy(const std::string& path, const ProgressRange& progress) {
  StoredHierarchy out;
  out.info = readHierarchyInfo(path, false);  // also refuses files tinlod did not write, and checks the levels
  if (out.info.kind == "catalogue")
    throw Error("'" + path + "' is a tinlod-tiles catalogue, not the hierarchy of one tile: give the catalogue itself");
  const char* const gpkgOnly[] = {"GPKG", nullptr};
  const DatasetPtr ds = openReadOnly(path, GDAL_OF_VECTOR, gpkgOnly);
  if (!ds) throw Error("'" + path + "' is not a GeoPackage GDAL can read");
  const bool levelled = out.info.kind == "hierarchy";
  OGRLayer& vertices = requiredLayer(*ds, path, "vertices", levelled);
  OGRLayer& triangles = requiredLayer(*ds, path, "triangles", levelled);
  Hierarchy& h = out.hierarchy;
  h.levels = out.info.levels;
  h.base.crsWkt = wktOf(triangles);
  h.base.crsName = out.info.crsName;
  readStoredVertices(StoredTable(path, vertices), h, levelled, out.info.bytes, progress.sub(0, 0.2));
  if (levelled) readStoredGroups(StoredTable(path, requiredLayer(*ds, path, "groups", true)), h);
  readStoredTriangles(StoredTable(path, triangles), h, levelled, out.info.bytes, progress.sub(0.2, 0.95));
  if (levelled) {
    linkStoredGroups(path, h);
    checkLevelCounts(path, h);
  } else {
    countSingleLevel(h);
  }
  readOptions(out.info, h);
  return out;
}

}  // namespace tinlod
