// SPDX-License-Identifier: GPL-3.0-or-later
#include "catalogue_lod.h"

#include <chrono>
#include <unordered_map>
#include <unordered_set>

#include "catalogue_hierarchy.h"
#include "tile_catalogue.h"
#include "tinlod/error.h"
#include "vertex_place.h"

namespace tinlod {
namespace {

using PlaceSet = std::unordered_set<Place, PlaceHash>;

// One tile's part of the output, from its last extraction.
struct TileLod {
  bool extracted = false;
  ExtractedLod part;                 // rows and columns the raster's
  std::vector<std::uint8_t> onLine;  // of part's vertices: on a line another tile shares
  std::vector<Place> line;           // the tile's vertices on lines it shares with other tiles
  std::size_t forced = 0;            // how many of them had come back when it was extracted
};

// Where the tiles start: a tile's last column (row) is a shared line when another starts there.
struct TileStarts {
  std::unordered_set<int> cols, rows;
  explicit TileStarts(const std::vector<CatalogueTile>& tiles) {
    for (const CatalogueTile& t : tiles) cols.insert(t.xoff), rows.insert(t.yoff);
  }
  bool onSharedLine(const CatalogueTile& t, const TinVertex& v) const {
    return (v.col == 0 && t.xoff > 0) || (v.row == 0 && t.yoff > 0) ||
           (v.col == t.xsize - 1 && cols.count(t.xoff + t.xsize - 1)) ||
           (v.row == t.ysize - 1 && rows.count(t.yoff + t.ysize - 1));
  }
};

std::size_t countIn(const PlaceSet& set, const std::vector<Place>& places) {
  std::size_t n = 0;
  for (const Place& p : places) n += set.count(p);
  return n;
}

// The triangles as the tile's part of the output.
void keepTriangles(const CatalogueTile& tile, const Hierarchy& h, const std::vector<std::uint32_t>& triangles,
                   const std::vector<std::uint8_t>& onLine, TileLod& out) {
  std::vector<VertexId> kept;
  out.part = extractedLod(h, triangles, &kept);
  for (TinVertex& v : out.part.tin.vertices) v.row += tile.yoff, v.col += tile.xoff;
  out.onLine.clear();
  for (VertexId v : kept) out.onLine.push_back(onLine[v]);
}

// Extracts one tile with the line vertices `back` holds forced back; adds those it brings
// back. True when it added one.
bool extractTile(const CatalogueTile& tile, const Hierarchy& h, const LodOptions& options, const TileStarts& starts,
                 PlaceSet& back, TileLod& out, double& seconds, const ProgressRange& progress) {
  LodVertices vertices;
  vertices.forced.assign(h.base.vertices.size(), 0);
  std::vector<VertexId> line;
  std::vector<std::uint8_t> onLine(h.base.vertices.size(), 0);
  out.line.clear();
  for (std::size_t v = 0; v < h.base.vertices.size(); ++v)
    if (starts.onSharedLine(tile, h.base.vertices[v])) {
      onLine[v] = 1;
      line.push_back(static_cast<VertexId>(v));
      out.line.push_back(placeOf(h.base.vertices[v]));
      vertices.forced[v] = back.count(out.line.back()) > 0;
    }
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::uint32_t> triangles = extractLod(h, options, progress, &vertices);
  seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  bool added = false;
  for (std::size_t i = 0; i < line.size(); ++i)
    if (vertices.back[line[i]]) added = back.insert(out.line[i]).second || added;
  keepTriangles(tile, h, triangles, onLine, out);
  out.forced = countIn(back, out.line);  // its own included: forcing them changes nothing
  out.extracted = true;
  return added;
}

void markSharedOutline(const std::unordered_map<Place, VertexId, PlaceHash>& shared, Tin& tin);

// The tiles' parts as one TIN: a vertex of a shared line once (only those are looked up).
void assemble(const std::vector<CatalogueTile>& tiles, const std::vector<TileLod>& parts, ExtractedLod& out) {
  std::unordered_map<Place, VertexId, PlaceHash> ids;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const ExtractedLod& part = parts[i].part;
    const std::vector<TinVertex>& vertices = part.tin.vertices;
    std::vector<VertexId> id(vertices.size());
    for (std::size_t v = 0; v < id.size(); ++v) {
      id[v] = static_cast<VertexId>(out.tin.vertices.size());
      if (parts[i].onLine[v]) {
        const auto [it, added] = ids.try_emplace(placeOf(vertices[v]), id[v]);
        id[v] = it->second;
        if (!added && (out.tin.vertices[id[v]].z != vertices[v].z || out.vertexLevel[id[v]] != part.vertexLevel[v]))
          throw Error(sharedVertexDiffers(tiles[i], vertices[v]));
        if (!added) continue;
      }
      out.tin.vertices.push_back(vertices[v]);
      out.vertexLevel.push_back(part.vertexLevel[v]);
    }
    for (const Triangle& t : part.tin.triangles) out.tin.triangles.push_back({id[t[0]], id[t[1]], id[t[2]]});
    out.firstLevel.insert(out.firstLevel.end(), part.firstLevel.begin(), part.firstLevel.end());
    out.lastLevel.insert(out.lastLevel.end(), part.lastLevel.begin(), part.lastLevel.end());
  }
  markSharedOutline(ids, out.tin);
}

// A vertex of a shared line is on each tile's own outline; in the union, only where an
// edge of it has a triangle on one side alone (nodata beyond, or the raster's edge).
void markSharedOutline(const std::unordered_map<Place, VertexId, PlaceHash>& shared, Tin& tin) {
  std::vector<std::uint8_t> isShared(tin.vertices.size(), 0);
  for (const auto& [place, v] : shared) isShared[v] = 1, tin.vertices[v].outline = false;
  const auto key = [](VertexId a, VertexId b) { return (std::uint64_t(a) << 32) | b; };
  std::unordered_set<std::uint64_t> edges;  // directed, of triangles with a shared corner
  for (const Triangle& t : tin.triangles)
    for (int k = 0; k < 3; ++k)
      if (isShared[t[k]] || isShared[t[(k + 1) % 3]]) edges.insert(key(t[k], t[(k + 1) % 3]));
  for (const std::uint64_t e : edges) {
    const VertexId a = VertexId(e >> 32), b = VertexId(e & 0xffffffffu);
    if (!edges.count(key(b, a))) {
      if (isShared[a]) tin.vertices[a].outline = true;
      if (isShared[b]) tin.vertices[b].outline = true;
    }
  }
}

}  // namespace

ExtractedLod extractCatalogueLod(const std::string& cataloguePath,
                                 const std::function<LodOptions(const std::string& crsWkt)>& optionsFor,
                                 const ProgressRange& progress) {
  const std::vector<CatalogueTile> tiles = readCatalogue(cataloguePath);
  requireTileCells(cataloguePath, tiles);
  warnOfUnfinishedTiles(cataloguePath, progress);
  const TileStarts starts(tiles);
  std::vector<TileLod> parts(tiles.size());
  PlaceSet back;
  Hierarchy job;
  LodOptions options;
  ExtractedLod out;
  for (bool again = true; again; ++out.passes) {
    again = false;
    // The first pass reads every tile; later ones only those whose lines gained a vertex.
    const auto share = [](int pass) { return 0.8 + 0.2 * (1 - 1.0 / pass); };  // done after `pass` passes
    const ProgressRange pass = out.passes == 1 ? progress.sub(0, 0.8) : progress.sub(share(out.passes - 1), share(out.passes));
    for (std::size_t i = 0; i < tiles.size(); ++i) {
      if (parts[i].extracted && countIn(back, parts[i].line) == parts[i].forced) continue;
      const ProgressRange part = pass.sub(double(i) / tiles.size(), double(i + 1) / tiles.size());
      part.report(0, "Extracting tile " + tiles[i].name + " (pass " + std::to_string(out.passes) + ")");
      const Hierarchy h = readCatalogueTile(tiles[i], part.sub(0, 0.8)).hierarchy;
      if (out.passes == 1 && i == 0) {
        job = jobOf(h);
        options = optionsFor(h.base.crsWkt);
      } else {
        checkSameJob(tiles[i], h, job);
      }
      if (out.passes == 1) out.levelZeroTriangles += h.levels.empty() ? 0 : h.levels[0].triangles;
      again = extractTile(tiles[i], h, options, starts, back, parts[i], out.seconds, part.sub(0.8, 1)) || again;
    }
  }
  --out.passes;
  out.tin.crsWkt = job.base.crsWkt, out.tin.crsName = job.base.crsName;
  out.coarsest = job.coarsest();
  assemble(tiles, parts, out);
  return out;
}

}  // namespace tinlod
