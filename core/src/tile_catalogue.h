// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "tinlod/feedback.h"

namespace tinlod {

// A finished tile of a catalogue written by tinlod-tiles: its hierarchy file and extent.
struct CatalogueTile {
  std::string name;  // "C,R"
  std::string file;  // resolved against the catalogue's folder
  std::array<double, 4> box{};  // min x, min y, max x, max y in the TIN's CRS
  int xoff = 0, yoff = 0;     // the tile's first column and row in the raster
  // Its cells across and down, the line it shares with the next tile included; 0 in a
  // catalogue that does not say.
  int xsize = 0, ysize = 0;
};

// Whether `path` is a tinlod-tiles catalogue (its metadata says so).
bool isCatalogue(const std::string& path);

// The catalogue's finished tiles (status 'done'). Throws Error when it has none.
std::vector<CatalogueTile> readCatalogue(const std::string& path);

// The tiles not finished (pending, failed, or empty: no triangle within the build's
// -valid_range): their cells only, no file or box.
std::vector<CatalogueTile> readUnfinishedTiles(const std::string& path);

// A tile as the catalogue lists it, whatever its status.
struct TileStatus {
  std::string name;    // "C,R"
  std::string status;  // pending, done, empty or failed
  std::string error;   // why it failed, when the catalogue says
  std::string file;    // resolved against the catalogue's folder; empty when it has none
};

// Every tile of the catalogue, in the catalogue's order.
std::vector<TileStatus> readTileStatuses(const std::string& path);

// What a job that reads the catalogue warns of when some of its tiles are not finished
// (pending or failed; an empty tile holds no data): the result covers the finished ones
// only. Empty when every tile is done or empty.
std::string unfinishedTilesWarning(const std::string& path);
// "N of the catalogue's M tiles are not finished (by status)", or "": what an output made
// from the finished tiles alone records (TINLOD_UNFINISHED_TILES, a report's title).
std::string unfinishedTiles(const std::string& path);
// Records unfinishedTiles, if any, as an output's TINLOD_UNFINISHED_TILES; returns them.
std::string addUnfinishedTiles(const std::string& path, std::map<std::string, std::string>& metadata);
// Warns of them through `progress`, if there are any.
void warnOfUnfinishedTiles(const std::string& path, const ProgressRange& progress);

// Counts of tiles by status as text: "2 done, 1 failed" (the map's order).
std::string statusCounts(const std::map<std::string, std::size_t>& counts);

// Throws Error unless every tile says which cells it holds (xsize and ysize), as the jobs
// that work a tile at a time need.
void requireTileCells(const std::string& path, const std::vector<CatalogueTile>& tiles);

// Throws Error unless a finished tile's file is there (a GDAL /vsi path is not looked for):
// the catalogue names it relative to itself, so its tiles folder must stay beside it.
void requireTileFile(const std::string& name, const std::string& file);

// The message for a finished tile whose file cannot be read (damaged, or not a tile), and
// the fix.
std::string unreadableTile(const std::string& name, const std::string& file, const std::string& why);

}  // namespace tinlod
