// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/hierarchy_info.h"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <map>
#include <memory>
#include <sstream>

#include "layer_crs.h"
#include "catalogue_info.h"
#include "gdal_handles.h"
#include "number_text.h"
#include "sqlite_in_use.h"
#include "stored_table.h"
#include "tile_catalogue.h"
#include "text_and_paths.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

LevelStats levelRow(const StoredTable& table, const OGRFeature& f) {
  const StoredRow row(table, f);
  const int optional[] = {table.optionalColumn("rmse"), table.optionalColumn("cells"),
                          table.optionalColumn("outline_vertices")};  // files from before these columns lack them
  auto count = [&](int column) { return row.integer(column, 0, kMaxStoredCount, "counts"); };
  LevelStats l;
  l.level = static_cast<std::int32_t>(row.integer(table.column("level"), 0, INT32_MAX - 1, "level numbers"));
  l.vertices = static_cast<std::size_t>(count(table.column("vertices")));
  l.triangles = static_cast<std::size_t>(count(table.column("triangles")));
  l.deleted = static_cast<std::size_t>(count(table.column("deleted")));
  l.selectSeconds = row.nonNegative(table.column("select_seconds"));
  l.deleteSeconds = row.nonNegative(table.column("delete_seconds"));
  l.maxError = row.nonNegative(table.column("max_error"));
  if (optional[0] >= 0) l.rmse = row.nonNegative(optional[0]);
  if (optional[1] >= 0) l.cells = count(optional[1]);
  if (optional[2] >= 0) l.outlineVertices = static_cast<std::size_t>(count(optional[2]));
  return l;
}

// A hierarchy's levels are the rows of its levels table, one for each of 0 to n - 1: the
// readers size their arrays by them and check every triangle's levels against them.
std::vector<LevelStats> readLevelTable(const std::string& path, OGRLayer& layer) {
  const StoredTable table(path, layer);
  std::map<std::int32_t, LevelStats> byLevel;
  for (auto& f : layer) {
    const LevelStats l = levelRow(table, *f);
    if (!byLevel.emplace(l.level, l).second)
      StoredRow(table, *f).damaged("repeats level " + std::to_string(l.level));
  }
  table.checkFullyRead();
  if (byLevel.empty()) table.damaged("has no rows");
  if (byLevel.rbegin()->first > kMaxLevel)
    table.damaged("has level " + std::to_string(byLevel.rbegin()->first) + ", above the " + std::to_string(kMaxLevel) +
                  " a hierarchy may have");
  std::vector<LevelStats> levels;
  for (const auto& [level, l] : byLevel) {
    if (level != static_cast<std::int32_t>(levels.size()))
      table.damaged("has no row for level " + std::to_string(levels.size()) + " but one for level " +
                    std::to_string(level));
    levels.push_back(l);
  }
  return levels;
}

// A plain TIN is one level; its figures are for display only (the reader counts the rows
// it reads), so a feature count the file misstates does no harm.
LevelStats singleLevel(GDALDataset& ds, const HierarchyInfo& info) {
  auto rows = [&ds](const char* name) {
    OGRLayer* layer = ds.GetLayerByName(name);
    return layer ? static_cast<std::size_t>(std::max<GIntBig>(0, layer->GetFeatureCount())) : 0;
  };
  LevelStats l;
  l.vertices = rows("vertices"), l.triangles = rows("triangles");
  // A single TIN is not measured against the DEM when written (tinlod accuracy does that):
  // unknown, not zero. Greedy insertion records its maximum over its candidates (max_error),
  // which with -candidates samples are not every cell, and both figures over every valid
  // cell beside it: the row shows those, as a hierarchy's levels do.
  l.maxError = l.rmse = std::nan("");
  auto maxError = info.metadata.find("measured_max_error");
  if (maxError == info.metadata.end()) maxError = info.metadata.find("max_error");
  if (maxError != info.metadata.end()) l.maxError = std::strtod(maxError->second.c_str(), nullptr);
  if (const auto e = info.metadata.find("rmse"); e != info.metadata.end()) l.rmse = std::strtod(e->second.c_str(), nullptr);
  OGRLayer* vertices = ds.GetLayerByName("vertices");
  // The TIN's outline as its writer counted it; a file of an older tinlod has only the
  // sampler's flags, a count of the cells on the valid area's outline.
  if (const auto o = info.metadata.find("outline_vertices"); o != info.metadata.end()) {
    l.outlineVertices = static_cast<std::size_t>(std::strtoull(o->second.c_str(), nullptr, 10));
  } else if (vertices && vertices->GetLayerDefn()->GetFieldIndex("outline") >= 0 &&
             vertices->SetAttributeFilter("outline = 1") == OGRERR_NONE) {
    l.outlineVertices = static_cast<std::size_t>(std::max<GIntBig>(0, vertices->GetFeatureCount()));
    vertices->SetAttributeFilter(nullptr);
  }
  return l;
}

void readLevels(GDALDataset& ds, HierarchyInfo& info) {
  if (info.kind != "hierarchy") {
    info.levels.push_back(singleLevel(ds, info));
    return;
  }
  OGRLayer* levels = ds.GetLayerByName("levels");
  if (!levels)
    throwDamaged(info.path, "it is a hierarchy (TINLOD_KIND) but has no levels table; build it again with tinlod build");
  info.levels = readLevelTable(info.path, *levels);
}

HierarchyInfo catalogueInfo(GDALDataset& ds, HierarchyInfo info) {
  info.kind = "catalogue";
  if (OGRLayer* tiles = ds.GetLayerByName("tiles")) {
    const OGRSpatialReference* srs = layerCrs(*tiles);
    info.crsName = !srs ? "no CRS" : crsLabel(*srs);
  }
  for (int i = 0; i < ds.GetLayerCount(); ++i) info.layers.push_back(ds.GetLayer(i)->GetName());
  info.bytes = std::filesystem::file_size(info.path);
  addCatalogueContents(info);
  return info;
}

std::string tileCounts(const HierarchyInfo& info) {
  std::size_t all = 0;
  for (const auto& [status, count] : info.tileStatuses) all += count;
  return std::to_string(all) + (all == 1 ? " tile" : " tiles") + (all ? " (" + statusCounts(info.tileStatuses) + ")" : "");
}

// The commands take the catalogue, which holds the levels and how the tiles meet.
void refuseCatalogueLevel(const std::string& path) {
  const std::string catalogue = catalogueOfLevelFile(path);
  if (catalogue.empty() || !std::filesystem::exists(catalogue)) return;
  throw Error("'" + path + "' is " + std::filesystem::path(path).stem().string() + " of the tinlod-tiles catalogue '" +
              catalogue + "', drawn across its tiles: give the catalogue itself (tinlod info, lod, locate and accuracy " +
              "take it as one hierarchy)");
}

}  // namespace

std::string catalogueOfLevelFile(const std::string& path) {
  const std::filesystem::path file(path);
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  const std::string folder = file.parent_path().filename().string(), suffix = "_levels";
  if (extension != ".vrt" || folder.size() <= suffix.size() ||
      folder.compare(folder.size() - suffix.size(), suffix.size(), suffix) != 0)
    return "";
  return (file.parent_path().parent_path() / (folder.substr(0, folder.size() - suffix.size()) + ".gpkg")).string();
}

HierarchyInfo readHierarchyInfo(const std::string& path, bool withTiles) {
  GDALAllRegister();
  if (!std::filesystem::exists(path)) throw Error("'" + path + "' does not exist");
  refuseCatalogueLevel(path);
  refuseLockedForReading(path);
  const char* const gpkgOnly[] = {"GPKG", nullptr};
  const DatasetPtr ds = openReadOnly(path, GDAL_OF_VECTOR, gpkgOnly);
  if (!ds) {
    // GDAL opens a GeoPackage of rasters only as a raster: it is one, but holds no TIN.
    if (openReadOnly(path, GDAL_OF_RASTER, gpkgOnly))
      throw Error("'" + path + "' is a GeoPackage of rasters only, not a TIN tinlod wrote: give the GeoPackage of "
                  "tinlod build, sample or insert");
    if (sqliteFileLocked(path)) throw Error("'" + path + "' " + lockedFileWords() + ": try again once it is done");
    throw Error("'" + path + "' is not a GeoPackage GDAL can read");
  }
  HierarchyInfo info;
  info.path = path;
  if (char** md = ds->GetMetadata()) {
    for (char** item = md; *item; ++item) {
      std::string kv = *item;
      const auto eq = kv.find('=');
      if (kv.rfind("TINLOD_", 0) != 0 || eq == std::string::npos) continue;
      std::string key = kv.substr(7, eq - 7);
      for (char& c : key) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      info.metadata[key] = kv.substr(eq + 1);
    }
  }
  if (info.metadata.count("kind") && info.metadata["kind"] == "catalogue") {
    if (!withTiles) {
      info.kind = "catalogue";
      return info;
    }
    return catalogueInfo(*ds, std::move(info));
  }
  const auto kind = info.metadata.find("kind");
  if (kind != info.metadata.end() && kind->second == "merged_level")
    throw Error("'" + path + "' is level " + info.metadata["level"] + " of the tiles catalogue " +
                info.metadata["catalogue"] + ", merged by tinlod-tiles merge into one layer to draw: " +
                "tinlod info, lod, locate and accuracy take the catalogue itself");
  if (!ds->GetLayerByName("triangles") && kind != info.metadata.end() && kind->second != "tin" &&
      kind->second != "hierarchy" && kind->second != "lod")
    throw Error("'" + path + "' is a tinlod " + kind->second + " output (of tinlod lines or locate), not a TIN or a " +
                "hierarchy: its layers and metadata are shown by ogrinfo -so, and it opens in QGIS as it is");
  if (!ds->GetLayerByName("triangles") || info.metadata.empty())
    throw Error("'" + path + "' was not written by tinlod (no tinlod metadata or triangles layer): give a GeoPackage "
                "tinlod build, sample or insert wrote, or a tinlod-tiles catalogue");
  info.kind = info.metadata.count("kind") ? info.metadata["kind"] : "tin";
  const OGRSpatialReference* srs = layerCrs(*ds->GetLayerByName("triangles"));
  info.crsName = !srs ? "no CRS" : crsLabel(*srs);
  for (int i = 0; i < ds->GetLayerCount(); ++i) info.layers.push_back(ds->GetLayer(i)->GetName());
  readLevels(*ds, info);
  info.bytes = std::filesystem::file_size(path);
  return info;
}

std::string toJson(const HierarchyInfo& info) {
  std::ostringstream out;
  out << std::setprecision(10);
  out << "{\n  \"path\": " << jsonString(info.path) << ",\n  \"kind\": " << jsonString(info.kind)
      << ",\n  \"crs\": " << jsonString(info.crsName) << ",\n  \"bytes\": " << info.bytes << ",\n  \"parameters\": {";
  bool first = true;
  for (const auto& [k, v] : info.metadata) {
    out << (first ? "\n" : ",\n") << "    " << jsonString(k) << ": " << jsonString(v);
    first = false;
  }
  out << "\n  },\n";
  if (info.kind == "catalogue") {
    out << "  \"tiles\": {";
    first = true;
    for (const auto& [status, count] : info.tileStatuses) {
      out << (first ? "" : ", ") << jsonString(status) << ": " << count;
      first = false;
    }
    out << "},\n  \"failed_tiles\": [";
    for (std::size_t i = 0; i < info.failedTiles.size(); ++i) out << (i ? ", " : "") << jsonString(info.failedTiles[i]);
    out << "],\n  \"unreadable_tiles\": [";
    for (std::size_t i = 0; i < info.unreadableTiles.size(); ++i) out << (i ? ", " : "") << jsonString(info.unreadableTiles[i]);
    out << "],\n  \"tile_bytes\": " << info.tileBytes << ",\n";
  }
  out << "  \"layers\": [";
  for (std::size_t i = 0; i < info.layers.size(); ++i) out << (i ? ", " : "") << jsonString(info.layers[i]);
  out << "],\n  \"levels\": [";
  for (std::size_t i = 0; i < info.levels.size(); ++i) {
    const LevelStats& l = info.levels[i];
    // A single TIN (sample, insert, lod) records no deletions, times or cells: null.
    const bool single = info.kind != "hierarchy" && info.kind != "catalogue";
    const auto count = [single](auto v) { return single ? std::string("null") : std::to_string(v); };
    std::ostringstream seconds;
    seconds << std::setprecision(10) << ", \"select_seconds\": " << l.selectSeconds << ", \"delete_seconds\": " << l.deleteSeconds;
    out << (i ? ",\n" : "\n") << "    {\"level\": " << l.level << ", \"vertices\": " << l.vertices
        << ", \"triangles\": " << l.triangles << ", \"deleted\": " << count(l.deleted)
        << (single ? std::string(", \"select_seconds\": null, \"delete_seconds\": null") : seconds.str())
        << ", \"max_error\": ";
    if (std::isfinite(l.maxError))
      out << l.maxError;
    else
      out << "null";  // JSON has no infinity
    out << ", \"rmse\": ";
    if (std::isfinite(l.rmse))
      out << l.rmse;
    else
      out << "null";  // not measured (a single TIN)
    out << ", \"cells\": " << count(l.cells) << ", \"cells_given_up\": "
        << count(info.levels.front().cells - l.cells) << ", \"outline_vertices\": ";
    if (info.kind == "catalogue")
      out << "null";  // the tiles' outlines run along their shared lines
    else
      out << l.outlineVertices;
    out << "}";
  }
  out << "\n  ]\n}\n";
  return out.str();
}

std::string toText(const HierarchyInfo& info) {
  std::ostringstream out;
  const bool catalogue = info.kind == "catalogue";
  out << info.path << ": tinlod " << info.kind << ", " << info.crsName << ", " << std::fixed << std::setprecision(1)
      << info.bytes / 1e6 << " MB";
  if (catalogue) out << "; " << tileCounts(info) << ", " << info.tileBytes / 1e6 << " MB in the finished tiles";
  out << "\n";
  for (const auto& [k, v] : info.metadata) out << "  " << k << " = " << v << "\n";
  for (const std::string& failed : info.failedTiles) out << "  failed tile " << failed << "\n";
  for (const std::string& unreadable : info.unreadableTiles) out << "  unreadable: " << unreadable << "\n";
  if (catalogue)
    out << "  levels: the " << (info.unreadableTiles.empty() ? "" : "readable ")
        << "finished tiles' rows added up: a vertex or cell on a line two tiles share is counted\n"
           "  in each, times are summed, the maximum error is the largest, outlines are not counted;\n"
           "  tinlod accuracy measures the tiles as one TIN\n";
  out << std::setw(6) << "level" << std::setw(11) << "vertices" << std::setw(11) << "triangles" << std::setw(10)
      << "deleted" << std::setw(10) << "select s" << std::setw(10) << "delete s" << std::setw(12) << "max error m" << std::setw(9) << "RMSE m"
      << std::setw(10) << "outline" << std::setw(15) << "net cells lost" << "\n";
  // Each number one character narrower than its column: a space always separates them.
  // A single TIN (sample, insert, lod) has no deletions, times or cells of its own.
  const bool single = !catalogue && info.kind != "hierarchy";
  const auto known = [](double v, int decimals, int width) { return std::isfinite(v) ? columnNumber(v, decimals, width) : "-"; };
  // Centimetres of a LiDAR TIN read "0.03" and "0.01" to two decimals: as many as show them.
  double largest = 0;
  for (const LevelStats& l : info.levels)
    if (std::isfinite(l.maxError)) largest = std::max(largest, l.maxError);
  const int errorDecimals = largest >= 1 || largest == 0 ? 2 : largest >= 0.1 ? 3 : 4;
  for (const LevelStats& l : info.levels) {
    const std::string outline = catalogue ? "-" : std::to_string(l.outlineVertices);
    out << std::setw(6) << l.level << std::setw(11) << l.vertices << std::setw(11) << l.triangles << std::setw(10)
        << (single ? "-" : std::to_string(l.deleted)) << std::setw(10) << (single ? "-" : columnNumber(l.selectSeconds, 3, 9))
        << std::setw(10) << (single ? "-" : columnNumber(l.deleteSeconds, 3, 9)) << std::setw(12) << known(l.maxError, errorDecimals, 11)
        << std::setw(9) << known(l.rmse, errorDecimals, 8) << std::setw(10) << outline << std::setw(15)
        << (single ? "-" : std::to_string(info.levels.front().cells - l.cells)) << "\n";
  }
  return out.str();
}

}  // namespace tinlod
