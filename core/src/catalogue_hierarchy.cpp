// SPDX-License-Identifier: GPL-3.0-or-later
#include "catalogue_hierarchy.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "tile_catalogue.h"
#include "tin_outline.h"
#include "vertex_place.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

// Appends tiles to one hierarchy, one vertex for each place.
class TileMerger {
 public:
  void add(const CatalogueTile& tile, const Hierarchy& h);
  Hierarchy finish();

 private:
  std::vector<VertexId> addVertices(const CatalogueTile& tile, const Hierarchy& h);
  void addTriangles(const Hierarchy& h, const std::vector<VertexId>& id);

  Hierarchy all_;
  PooledLevels levels_;
  std::unordered_map<Place, VertexId, PlaceHash> places_;
  bool first_ = true;
};

std::vector<VertexId> TileMerger::addVertices(const CatalogueTile& tile, const Hierarchy& h) {
  std::vector<VertexId> id(h.base.vertices.size());
  for (std::size_t v = 0; v < id.size(); ++v) {
    TinVertex vertex = h.base.vertices[v];
    vertex.row += tile.yoff, vertex.col += tile.xoff;  // the tile's cell, in the whole raster
    const bool fixed = !h.fixed.empty() && h.fixed[v];
    const auto [it, added] = places_.try_emplace(placeOf(vertex), static_cast<VertexId>(all_.base.vertices.size()));
    id[v] = it->second;
    if (added) {
      all_.base.vertices.push_back(vertex);
      all_.vertexLevel.push_back(h.vertexLevel[v]);
      all_.fixed.push_back(fixed);
      continue;
    }
    // A vertex of a line this tile shares with one read before.
    if (all_.base.vertices[id[v]].z != vertex.z || all_.vertexLevel[id[v]] != h.vertexLevel[v])
      throw Error(sharedVertexDiffers(tile, vertex));
    all_.fixed[id[v]] = all_.fixed[id[v]] || fixed;
  }
  return id;
}

void TileMerger::addTriangles(const Hierarchy& h, const std::vector<VertexId>& id) {
  const auto remap = [&](Triangle t) { return Triangle{id[t[0]], id[t[1]], id[t[2]]}; };
  const auto groupOffset = static_cast<std::int32_t>(all_.groups.size());
  const auto triangleOffset = static_cast<std::uint32_t>(all_.triangles.size());
  const auto linkOffset = static_cast<std::uint32_t>(all_.links.size());
  for (const Triangle& t : h.base.triangles) all_.base.triangles.push_back(remap(t));
  for (HierarchyTriangle t : h.triangles) {
    t.v = remap(t.v);
    if (t.group != kNoGroup) t.group += groupOffset;
    if (t.replacedBy != kNoGroup) t.replacedBy += groupOffset;
    all_.triangles.push_back(t);
  }
  for (Group g : h.groups) {
    g.vertex = id[g.vertex];
    g.acceptBegin += linkOffset, g.acceptEnd += linkOffset, g.rejectBegin += linkOffset, g.rejectEnd += linkOffset;
    g.ringBegin = g.ringEnd = 0;  // a stored hierarchy has no rings
    all_.groups.push_back(g);
  }
  for (std::uint32_t t : h.links) all_.links.push_back(t + triangleOffset);
  if (all_.triangles.size() > UINT32_MAX || all_.groups.size() > std::size_t(INT32_MAX))
    throw Error("the catalogue's tiles hold more triangles than one hierarchy can: use fewer tiles (tinlod tiles merge -te)");
}

void TileMerger::add(const CatalogueTile& tile, const Hierarchy& h) {
  if (first_) {
    all_.base.crsWkt = h.base.crsWkt, all_.base.crsName = h.base.crsName;
    all_.options = h.options, all_.tinMethod = h.tinMethod;
    all_.levels = h.levels;  // what checkSameJob compares the next tiles with
  } else {
    checkSameJob(tile, h, all_);
  }
  levels_.add(h.levels);
  addTriangles(h, addVertices(tile, h));
  if (!h.stopReason.empty() && all_.stopReason.empty()) all_.stopReason = "tile " + tile.name + ": " + h.stopReason;
  first_ = false;
}

Hierarchy TileMerger::finish() {
  // Tiles' shared lines are no longer outline once the tiles are put together.
  const std::vector<bool> outline = outlineVertices(all_.base);
  for (std::size_t v = 0; v < outline.size(); ++v) all_.base.vertices[v].outline = outline[v];
  all_.levels = levels_.finish();
  for (std::size_t L = 0; L < all_.levels.size(); ++L) {
    LevelStats& s = all_.levels[L];
    s.vertices = s.deleted = s.outlineVertices = 0;
    for (std::size_t v = 0; v < all_.vertexLevel.size(); ++v) {
      s.vertices += all_.vertexLevel[v] >= std::int32_t(L);
      s.deleted += L > 0 && all_.vertexLevel[v] == std::int32_t(L) - 1;
      s.outlineVertices += outline[v] && all_.vertexLevel[v] >= std::int32_t(L);
    }
  }
  return std::move(all_);
}

}  // namespace

std::string notOneJob(const CatalogueTile& tile, const std::string& what) {
  return "tile " + tile.name + " ('" + tile.file + "') " + what + ": the catalogue's tiles were not built by one job";
}

std::string sharedVertexDiffers(const CatalogueTile& tile, const TinVertex& v) {
  return notOneJob(tile, "and a tile beside it have a vertex at x " + std::to_string(v.x) + ", y " + std::to_string(v.y) +
                             " with another height or level");
}

void poolLevelStats(LevelStats& pooled, const LevelStats& tile) {
  pooled.triangles += tile.triangles, pooled.cells += tile.cells;
  pooled.selectSeconds += tile.selectSeconds, pooled.deleteSeconds += tile.deleteSeconds;
  pooled.maxError = std::max(pooled.maxError, tile.maxError);
}

void PooledLevels::add(const std::vector<LevelStats>& tile) {
  const bool first = levels_.empty();
  if (first) levels_ = tile, squares_.assign(tile.size(), 0);
  for (std::size_t L = 0; L < tile.size(); ++L) {
    if (!first) poolLevelStats(levels_[L], tile[L]);
    squares_[L] += tile[L].rmse * tile[L].rmse * double(tile[L].cells);
  }
}

std::vector<LevelStats> PooledLevels::finish() {
  for (std::size_t L = 0; L < levels_.size(); ++L)
    levels_[L].rmse = levels_[L].cells > 0 ? std::sqrt(squares_[L] / double(levels_[L].cells)) : 0;
  return std::move(levels_);
}

void requireOwnTile(const std::string& name, const std::string& file, const HierarchyInfo& info) {
  // A file copied or renamed over another tile's would put its triangles in the wrong place.
  const auto holds = info.metadata.find("tile");
  if (holds != info.metadata.end() && holds->second != name)
    throw Error("tile " + name + " ('" + file + "') holds tile " + holds->second +
                ": remove the file and run tinlod tiles again to build it");
}

StoredHierarchy readCatalogueTile(const CatalogueTile& tile, const ProgressRange& progress) {
  requireTileFile(tile.name, tile.file);
  StoredHierarchy stored;
  try {
    stored = readHierarchy(tile.file, progress);
  } catch (const Cancelled&) {
    throw;
  } catch (const Error& e) {
    throw Error(unreadableTile(tile.name, tile.file, e.what()));
  }
  if (stored.info.kind != "hierarchy")
    throw Error("tile " + tile.name + " ('" + tile.file + "') is a single TIN, not a hierarchy: build the tiles with tinlod tiles");
  requireOwnTile(tile.name, tile.file, stored.info);
  // Under -max_error a tile that refused line vertices is built again with its neighbours
  // until none does: a run stopped before then leaves tiles that do not meet on their lines.
  const auto refused = stored.info.metadata.find("border_refused");
  if (refused != stored.info.metadata.end() && !refused->second.empty())
    throw Error("tile " + tile.name + " ('" + tile.file + "') refuses line vertices its neighbours may have deleted: the "
                "catalogue's -max_error run stopped before its tiles agreed their shared lines, so they do not meet "
                "there yet; run tinlod tiles on it again to finish them");
  return stored;
}

Hierarchy jobOf(const Hierarchy& h) {
  Hierarchy job;
  job.levels = h.levels;
  job.base.crsWkt = h.base.crsWkt, job.base.crsName = h.base.crsName;
  job.options = h.options;
  job.tinMethod = h.tinMethod;
  return job;
}

void checkSameJob(const CatalogueTile& tile, const Hierarchy& h, const Hierarchy& before) {
  if (h.coarsest() != before.coarsest())
    throw Error(notOneJob(tile, "has levels 0 to " + std::to_string(h.coarsest()) + ", the tiles before it 0 to " +
                                    std::to_string(before.coarsest())));
  if (h.base.crsWkt != before.base.crsWkt) throw Error(notOneJob(tile, "has another CRS than the tiles before it"));
  if (h.options.measure != before.options.measure || h.options.deletePct != before.options.deletePct ||
      h.options.stopPct != before.options.stopPct || h.tinMethod != before.tinMethod)
    throw Error(notOneJob(tile, "was simplified with other options than the tiles before it"));
}

StoredHierarchy readCatalogueHierarchy(const std::string& path, const ProgressRange& progress) {
  const std::vector<CatalogueTile> tiles = readCatalogue(path);
  TileMerger merger;
  StoredHierarchy out;
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    const ProgressRange part = progress.sub(double(i) / tiles.size(), double(i + 1) / tiles.size());
    part.report(0, "Reading tile " + tiles[i].name + " (" + std::to_string(i + 1) + " of " + std::to_string(tiles.size()) + ")");
    StoredHierarchy tile = readCatalogueTile(tiles[i], part);
    merger.add(tiles[i], tile.hierarchy);
    if (i == 0) out.info = std::move(tile.info);
    else out.info.bytes += tile.info.bytes;
  }
  out.hierarchy = merger.finish();
  out.info.path = path;
  out.info.levels = out.hierarchy.levels;
  return out;
}

std::vector<std::string> hierarchyInputs(const std::string& path) {
  std::vector<std::string> files{path};
  if (isCatalogue(path))
    for (const CatalogueTile& tile : readCatalogue(path)) files.push_back(tile.file);
  return files;
}

StoredHierarchy readHierarchyOrCatalogue(const std::string& path, const ProgressRange& progress) {
  return isCatalogue(path) ? readCatalogueHierarchy(path, progress) : readHierarchy(path, progress);
}

}  // namespace tinlod
