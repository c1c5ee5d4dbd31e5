// SPDX-License-Identifier: GPL-3.0-or-later
#include "tile_catalogue.h"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <filesystem>
#include <map>
#include <memory>

#include "sqlite_in_use.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

struct Closer {
  void operator()(GDALDataset* ds) const { GDALClose(ds); }
};
using Dataset = std::unique_ptr<GDALDataset, Closer>;

Dataset openVector(const std::string& path) {
  GDALAllRegister();  // isCatalogue may be the first GDAL call (a job's list of its inputs)
  CPLPushErrorHandler(CPLQuietErrorHandler);
  GDALDataset* ds = static_cast<GDALDataset*>(
      GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
  CPLPopErrorHandler();
  return Dataset(ds);
}

}  // namespace

bool isCatalogue(const std::string& path) {
  const std::filesystem::path p(path);
  if (!std::filesystem::is_regular_file(p)) return false;
  refuseLockedForReading(path);  // every reader of a TIN file asks this first
  const Dataset ds = openVector(path);
  const char* kind = ds ? ds->GetMetadataItem("TINLOD_KIND") : nullptr;
  return kind && std::string(kind) == "catalogue";
}

namespace {

OGRLayer& tilesLayer(const std::string& path, const Dataset& ds) {
  OGRLayer* layer = ds ? ds->GetLayerByName("tiles") : nullptr;
  if (!layer) throw Error("'" + path + "' is not a tinlod-tiles catalogue: it has no 'tiles' layer");
  return *layer;
}

std::string tileName(const OGRFeature& f) {
  return std::to_string(f.GetFieldAsInteger("tile_col")) + "," + std::to_string(f.GetFieldAsInteger("tile_row"));
}

// A tile's file, resolved against the catalogue's folder (the catalogue names it relative
// to that folder, so that the folder can move).
std::string tileFile(const std::string& path, const OGRFeature& f) {
  const std::filesystem::path file = f.GetFieldAsString("file");
  return (file.is_absolute() ? file : std::filesystem::path(path).parent_path() / file).string();
}

// The catalogue's tiles whose status `wanted` accepts; `withFile`: only those with a
// geometry, their file resolved.
template <class Wanted>
std::vector<CatalogueTile> tilesWhere(const std::string& path, Wanted wanted, bool withFile) {
  const Dataset ds = openVector(path);
  OGRLayer* layer = &tilesLayer(path, ds);
  const bool sized = layer->GetLayerDefn()->GetFieldIndex("xsize") >= 0 && layer->GetLayerDefn()->GetFieldIndex("ysize") >= 0;
  std::vector<CatalogueTile> tiles;
  for (auto& f : *layer) {
    if (!wanted(std::string(f->GetFieldAsString("status")))) continue;
    CatalogueTile t;
    t.name = tileName(*f);
    t.xoff = f->GetFieldAsInteger("xoff"), t.yoff = f->GetFieldAsInteger("yoff");
    if (sized) t.xsize = f->GetFieldAsInteger("xsize"), t.ysize = f->GetFieldAsInteger("ysize");
    if (withFile) {
      const OGRGeometry* g = f->GetGeometryRef();
      if (!g) continue;
      OGREnvelope e;
      g->getEnvelope(&e);
      t.file = tileFile(path, *f);
      t.box = {e.MinX, e.MinY, e.MaxX, e.MaxY};
    }
    tiles.push_back(std::move(t));
  }
  return tiles;
}

}  // namespace

std::vector<CatalogueTile> readCatalogue(const std::string& path) {
  std::vector<CatalogueTile> tiles = tilesWhere(path, [](const std::string& s) { return s == "done"; }, true);
  if (tiles.empty()) throw Error("the catalogue '" + path + "' has no finished tile: run tinlod tiles on it first");
  return tiles;
}

std::vector<CatalogueTile> readUnfinishedTiles(const std::string& path) {
  return tilesWhere(path, [](const std::string& s) { return s != "done"; }, false);
}

std::vector<TileStatus> readTileStatuses(const std::string& path) {
  const Dataset ds = openVector(path);
  OGRLayer& layer = tilesLayer(path, ds);
  const bool hasError = layer.GetLayerDefn()->GetFieldIndex("error") >= 0;
  std::vector<TileStatus> tiles;
  for (auto& f : layer) {
    TileStatus t{tileName(*f), f->GetFieldAsString("status"), hasError ? f->GetFieldAsString("error") : "", ""};
    if (f->IsFieldSetAndNotNull(f->GetFieldIndex("file"))) t.file = tileFile(path, *f);
    tiles.push_back(std::move(t));
  }
  return tiles;
}

std::string unfinishedTiles(const std::string& path) {
  std::map<std::string, std::size_t> unfinished;
  std::size_t all = 0, count = 0;
  for (const TileStatus& tile : readTileStatuses(path)) {
    ++all;
    if (tile.status != "done" && tile.status != "empty") ++unfinished[tile.status], ++count;
  }
  if (count == 0) return "";
  return std::to_string(count) + " of the catalogue's " + std::to_string(all) + " tiles " + (count == 1 ? "is" : "are") +
         " not finished (" + statusCounts(unfinished) + ")";
}

std::string addUnfinishedTiles(const std::string& path, std::map<std::string, std::string>& metadata) {
  const std::string unfinished = unfinishedTiles(path);
  if (!unfinished.empty()) metadata["TINLOD_UNFINISHED_TILES"] = unfinished + ": the finished tiles alone";
  return unfinished;
}

std::string unfinishedTilesWarning(const std::string& path) {
  const std::string unfinished = unfinishedTiles(path);
  return unfinished.empty() ? "" : unfinished + ": only the finished tiles are read; run tinlod tiles again to finish them";
}

void warnOfUnfinishedTiles(const std::string& path, const ProgressRange& progress) {
  if (const std::string warning = unfinishedTilesWarning(path); !warning.empty()) progress.warn(warning);
}

std::string statusCounts(const std::map<std::string, std::size_t>& counts) {
  std::string text;
  for (const auto& [status, n] : counts) text += (text.empty() ? "" : ", ") + std::to_string(n) + " " + status;
  return text;
}

void requireTileFile(const std::string& name, const std::string& file) {
  if (file.rfind("/vsi", 0) != 0 && !std::filesystem::exists(file))
    throw Error("tile " + name + "'s file '" + file + "' does not exist: the catalogue names its tiles' files "
                "relative to itself, so its tiles folder must stay beside it; move the folder back, or run tinlod tiles "
                "on the catalogue again to build the tile");
}

std::string unreadableTile(const std::string& name, const std::string& file, const std::string& why) {
  return "tile " + name + " ('" + file + "') cannot be read: " + why +
         "; remove the file and run tinlod tiles on the catalogue again to build it";
}

void requireTileCells(const std::string& path, const std::vector<CatalogueTile>& tiles) {
  for (const CatalogueTile& tile : tiles)
    if (tile.xsize < 2 || tile.ysize < 2)
      throw Error("the catalogue '" + path + "' does not record the cells of tile " + tile.name +
                  " (its xsize and ysize): make it again with tinlod tiles");
}

}  // namespace tinlod
