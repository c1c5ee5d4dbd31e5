// SPDX-License-Identifier: GPL-3.0-or-later
#include "dataset_files.h"
#include "tinlod/locate_job.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <filesystem>
#include <functional>
#include <numeric>
#include <vector>

#include "layer_crs.h"
#include "gdal_handles.h"
#include "gpkg_output.h"
#include "layer_source.h"
#include "layer_transform.h"
#include "point_geometry.h"
#include "point_surface.h"
#include "tile_catalogue.h"
#include "text_and_paths.h"
#include "tinlod/error.h"
#include "tinlod/hierarchy_locator.h"
#include "tinlod/hierarchy_reader.h"
#include "tinlod/version.h"

namespace tinlod {
namespace {

bool isTinlodFile(const std::string& path) {
  try {
    readHierarchyInfo(path);
    return true;
  } catch (const Error&) {
    return false;
  }
}

// A feature's position, or false when it has no geometry (it is copied without values).
// Each feature gets one elevation: a multipoint of several points is refused.
bool pointOf(const OGRFeature& f, const std::string& path, double& x, double& y) {
  std::vector<std::array<double, 2>> points;
  appendPoints(f, "points", path, points);
  if (points.size() > 1)
    throw Error("points: feature " + std::to_string(f.GetFID()) + " of '" + path + "' is a multipoint of " +
                std::to_string(points.size()) +
                " points, and locate gives each feature one elevation: split it into single points first "
                "(QGIS: Multipart to singleparts)");
  if (points.empty()) return false;
  x = points[0][0], y = points[0][1];
  return true;
}

OGRLayer* createPointsLayer(GpkgOutput& out, OGRLayer& source, bool tiled) {
  const OGRSpatialReference* srs = layerCrs(source);
  const std::string wkt = srs ? wkt2(*srs) : std::string();
  OGRLayer* layer = out.createLayer("points", source.GetGeomType(), wkt, {});  // as the points are stored
  OGRFeatureDefn* defn = source.GetLayerDefn();
  for (int i = 0; i < defn->GetFieldCount(); ++i)
    if (layer->CreateField(defn->GetFieldDefn(i)) != OGRERR_NONE)
      throw Error("cannot copy the field '" + std::string(defn->GetFieldDefn(i)->GetNameRef()) + "' of the points");
  std::vector<const char*> added{"elevation", "triangle"};
  if (tiled) added.push_back("tile");  // a catalogue's triangle ids are its tile's
  for (const char* name : added) {
    if (defn->GetFieldIndex(name) >= 0)
      throw Error("the points already have a field '" + std::string(name) + "': rename it first");
    const std::string n = name;
    OGRFieldDefn field(name, n == "elevation" ? OFTReal : n == "tile" ? OFTString : OFTInteger);
    layer->CreateField(&field);
  }
  return layer;
}

// Points are located a chunk at a time, in the order of the tiles that hold them, and
// written in their own order: points in any order would read a catalogue's tiles again and
// again (only a few are kept), and the chunk bounds the memory whatever the layer's size.
constexpr std::size_t kChunk = std::size_t{1} << 16;

struct PendingPoint {
  OGRFeatureUniquePtr feature;  // as it is written: the source's fields and geometry, and ours
  double x = 0, y = 0;          // in the TIN's CRS
  bool placed = false;          // it has one point, and the CRS transformation took it
  std::size_t tile = 0;         // PointSurface::firstTileAt
};

struct OutputFields {
  int elevation, triangle, tile;
};

void locateChunk(std::vector<PendingPoint>& chunk, PointSurface& surface, int level, const OutputFields& fields,
                 LocateSummary& s, const std::function<void()>& checkCancel) {
  std::vector<std::size_t> order(chunk.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return chunk[a].tile < chunk[b].tile; });
  std::string tile;
  std::size_t lastTile = ~std::size_t{0};
  for (std::size_t i : order) {
    PendingPoint& point = chunk[i];
    if (!point.placed) continue;
    if (point.tile != lastTile) checkCancel(), lastTile = point.tile;  // before each tile's read
    const auto start = std::chrono::steady_clock::now();
    const LocatedPoint p = surface.locate(point.x, point.y, level, point.tile, tile);
    s.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!p.found()) continue;
    point.feature->SetField(fields.elevation, p.z);
    point.feature->SetField(fields.triangle, static_cast<GIntBig>(p.triangle) + 1);
    if (fields.tile >= 0) point.feature->SetField(fields.tile, tile.c_str());
    ++s.located;
  }
}

}  // namespace

LocateSummary runLocateJob(const std::string& hierarchyPath, const std::string& pointsPath, const std::string& outPath,
                           int level, bool overwrite, const Feedback& feedback) {
  if (plainPathMissing(parseLayerSource(pointsPath, "points").path))  // before the long work
    throw Error("points: '" + pointsPath + "' does not exist");
  GpkgWriteOptions writeOptions{overwrite, {{"TINLOD_VERSION", kVersion}, {"TINLOD_KIND", "points"},
                                            {"TINLOD_SOURCE", recordedPath(hierarchyPath)}, {"TINLOD_LEVEL", std::to_string(level)}}};
  // An input named as the output is refused as such first (not as a file of another kind).
  OutputFiles files(overwrite, datasetFiles({hierarchyPath, pointsPath}));
  files.refuseInput(outPath, "output");
  checkOutputPath(outPath, writeOptions);
  // Its metadata would replace the file's own: a hierarchy would stop being one.
  if (std::filesystem::exists(outPath) && isTinlodFile(outPath))
    throw Error("'" + outPath + "' is a tinlod GeoPackage: write the points to another file");
  const StagedFile& staged = files.add(outPath, "output", true);
  const ProgressRange all(feedback, 0, 1);
  PointSurface surface(hierarchyPath, all.sub(0, 0.4));
  LocateSummary s;
  if (surface.tiled()) s.unfinishedTiles = addUnfinishedTiles(hierarchyPath, writeOptions.metadata);
  if (level == -1) level = surface.coarsest(), writeOptions.metadata["TINLOD_LEVEL"] = std::to_string(level);  // as accuracy's -level
  if (level < 0 || level > surface.coarsest())
    throw Error("-level " + std::to_string(level) + " does not exist: '" + hierarchyPath + "' has levels 0 to " +
                std::to_string(surface.coarsest()));
  const OpenLayer open = openLayer(pointsPath, "points");
  OGRLayer& source = *open.layer;
  checkPointLayer(source, "points", open.path);
  const auto transform = transformToTin(source, surface.crsWkt(), "points ('" + pointsPath + "')", all);

  GpkgOutput out(staged, writeOptions, [](const std::string& name) { return name == "points"; });
  OGRLayer* layer = createPointsLayer(out, source, surface.tiled());
  const OGRFeatureDefn& defn = *layer->GetLayerDefn();
  const OutputFields fields{defn.GetFieldIndex("elevation"), defn.GetFieldIndex("triangle"),
                            defn.GetFieldIndex("tile")};
  out.begin();
  s.level = level;
  const GIntBig count = std::max<GIntBig>(1, source.GetFeatureCount());
  std::vector<PendingPoint> chunk;
  const auto flush = [&] {
    locateChunk(chunk, surface, level, fields, s,
                [&] { all.report(0.4 + 0.4 * double(s.points) / count, "Locating points"); });
    for (PendingPoint& point : chunk) writeFeature(*layer, *point.feature);
    chunk.clear();
  };
  for (auto& f : source) {
    PendingPoint point{OGRFeatureUniquePtr(OGRFeature::CreateFeature(layer->GetLayerDefn()))};
    point.feature->SetFrom(f.get(), TRUE);
    point.placed =
        pointOf(*f, open.path, point.x, point.y) && (!transform || transform->Transform(1, &point.x, &point.y));
    if (point.placed) point.tile = surface.firstTileAt(point.x, point.y);
    chunk.push_back(std::move(point));
    if (chunk.size() == kChunk) flush();
    if ((++s.points & 0x3FFF) == 0) all.report(0.4 + 0.4 * double(s.points) / count, "Locating points");
  }
  flush();
  // Every elevation null is most often the points' CRS (a CSV without one is taken as the
  // TIN's), which a count alone does not show.
  if (s.points > 0 && s.located == 0)
    all.warn("none of the " + std::to_string(s.points) + " points lies on the TIN of level " + std::to_string(level) +
             " (their elevations are null): are they in the CRS their layer says (one without a CRS is taken as the TIN's) " +
             "and on its data?");
  out.commit();
  out.finish(all.sub(0.8, 1));
  files.commit();
  s.tilesRead = surface.tilesRead();
  all.finish("Done");
  return s;
}

}  // namespace tinlod
