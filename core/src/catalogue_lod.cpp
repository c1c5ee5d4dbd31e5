// SPDX-License-Identifier: GPL-3.0-or-later
#include "catalogue_lod.h"

#include <stdlib.h>

#include <algorithm>
#include <chrono>
#include <unordered_map>
#include <unordered_set>

#include "catalogue_hierarchy.h"
#include "lod_part_files.h"
#include "tile_catalogue.h"
#include "tin_outline.h"
#include "tinlod/error.h"
#include "vertex_place.h"

namespace tinlod {
namespace fs = std::filesystem;
namespace {

using PlaceSet = std::unordered_set<Place, PlaceHash>;

// What the passes keep of a tile between its extractions (its part waits in a file).
struct TileLines {
  bool extracted = false;
  std::vector<Place> line;  // the tile's vertices on lines it shares with other tiles
  std::size_t forced = 0;   // how many of them had come back when it was extracted
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
TileLodPart partOf(const CatalogueTile& tile, const Hierarchy& h, const std::vector<std::uint32_t>& triangles,
                   const std::vector<std::uint8_t>& onLine) {
  std::vector<VertexId> kept;
  TileLodPart out;
  out.lod = extractedLod(h, triangles, &kept);
  for (TinVertex& v : out.lod.tin.vertices) v.row += tile.yoff, v.col += tile.xoff;
  for (VertexId v : kept) out.onLine.push_back(onLine[v]);
  return out;
}

// Extracts one tile with the line vertices `back` holds forced back, into its part's file;
// adds those it brings back. True when it added one.
bool extractTile(std::size_t i, const CatalogueTile& tile, const Hierarchy& h, const LodOptions& options,
                 const TileStarts& starts, const LodPartFiles& parts, PlaceSet& back, TileLines& out, double& seconds,
                 const ProgressRange& progress) {
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
  for (std::size_t k = 0; k < line.size(); ++k)
    if (vertices.back[line[k]]) added = back.insert(out.line[k]).second || added;
  parts.write(i, partOf(tile, h, triangles, onLine));
  out.forced = countIn(back, out.line);  // its own included: forcing them changes nothing
  out.extracted = true;
  return added;
}

// Every tile extracted until their lines agree, its part in its file.
CatalogueLodRun extractTiles(const std::vector<CatalogueTile>& tiles,
                             const std::function<LodOptions(const std::string& crsWkt)>& optionsFor,
                             const LodPartFiles& parts, Hierarchy& job, const ProgressRange& progress) {
  const TileStarts starts(tiles);
  std::vector<TileLines> lines(tiles.size());
  PlaceSet back;
  LodOptions options;
  CatalogueLodRun run;
  for (bool again = true; again; ++run.passes) {
    again = false;
    // The first pass reads every tile; later ones only those whose lines gained a vertex.
    const auto share = [](int pass) { return 0.8 + 0.2 * (1 - 1.0 / pass); };  // done after `pass` passes
    const ProgressRange pass = run.passes == 1 ? progress.sub(0, 0.8) : progress.sub(share(run.passes - 1), share(run.passes));
    for (std::size_t i = 0; i < tiles.size(); ++i) {
      if (lines[i].extracted && countIn(back, lines[i].line) == lines[i].forced) continue;
      const ProgressRange part = pass.sub(double(i) / tiles.size(), double(i + 1) / tiles.size());
      part.report(0, "Extracting tile " + tiles[i].name + " (pass " + std::to_string(run.passes) + ")");
      const Hierarchy h = readCatalogueTile(tiles[i], part.sub(0, 0.8)).hierarchy;
      if (run.passes == 1 && i == 0) {
        job = jobOf(h);
        options = optionsFor(h.base.crsWkt);
      } else {
        checkSameJob(tiles[i], h, job);
      }
      if (run.passes == 1) run.levelZeroTriangles += h.levels.empty() ? 0 : h.levels[0].triangles;
      again = extractTile(i, tiles[i], h, options, starts, parts, back, lines[i], run.seconds, part.sub(0.8, 1)) || again;
    }
  }
  --run.passes;
  run.coarsest = job.coarsest();
  return run;
}

// The tiles' parts numbered as one TIN: a vertex of a shared line once (only those are
// looked up), its outline set where an edge of it has a triangle on one side alone in the
// union (nodata beyond, or the raster's edge), not on each tile's own.
class Assembler {
 public:
  explicit Assembler(CatalogueLodSink& sink) : sink_(sink) {}

  void add(const CatalogueTile& tile, TileLodPart& part, const ProgressRange& progress) {
    std::vector<TinVertex>& vertices = part.lod.tin.vertices;
    std::vector<VertexId> id(vertices.size());
    std::vector<std::uint8_t> isNew(vertices.size(), 1);
    for (std::size_t v = 0; v < vertices.size(); ++v) {
      if (part.onLine[v]) {
        vertices[v].outline = false;
        const auto [it, added] = shared_.try_emplace(placeOf(vertices[v]), Shared{next_, vertices[v].z, part.lod.vertexLevel[v]});
        if (!added) {
          if (it->second.z != vertices[v].z || it->second.level != part.lod.vertexLevel[v])
            throw Error(sharedVertexDiffers(tile, vertices[v]));
          id[v] = it->second.id, isNew[v] = 0;
          continue;
        }
      }
      id[v] = next_++;
    }
    for (const Triangle& t : part.lod.tin.triangles)
      for (int k = 0; k < 3; ++k)
        if (part.onLine[t[k]] || part.onLine[t[(k + 1) % 3]]) edges_.insert(key(id[t[k]], id[t[(k + 1) % 3]]));
    // A vertex off the shared lines has all its triangles in this tile: its outline is the part's.
    const std::vector<bool> outline = outlineVertices(part.lod.tin);
    for (std::size_t v = 0; v < vertices.size(); ++v) outlineVertices_ += outline[v] && !part.onLine[v];
    sink_.add({part.lod, id, isNew}, progress);
  }

  void finish() {
    std::unordered_set<VertexId> isShared;
    for (const auto& [place, s] : shared_) isShared.insert(s.id);
    std::vector<VertexId> outline;
    for (const std::uint64_t e : edges_) {
      const VertexId a = VertexId(e >> 32), b = VertexId(e & 0xffffffffu);
      if (edges_.count(key(b, a))) continue;
      if (isShared.count(a)) outline.push_back(a);
      if (isShared.count(b)) outline.push_back(b);
    }
    std::sort(outline.begin(), outline.end());
    outline.erase(std::unique(outline.begin(), outline.end()), outline.end());
    sink_.setOutline(outline, outlineVertices_ + outline.size());
  }

 private:
  struct Shared {
    VertexId id;
    double z, level;
  };
  static std::uint64_t key(VertexId a, VertexId b) { return (std::uint64_t(a) << 32) | b; }
  CatalogueLodSink& sink_;
  std::unordered_map<Place, Shared, PlaceHash> shared_;
  std::unordered_set<std::uint64_t> edges_;  // directed, of triangles with a shared corner
  VertexId next_ = 0;
  std::size_t outlineVertices_ = 0;  // off the shared lines
};

// The output held whole.
class MemorySink : public CatalogueLodSink {
 public:
  explicit MemorySink(ExtractedLod& out) : out_(out) {}
  void start(const std::string& crsWkt, const std::string& crsName) override {
    out_.tin.crsWkt = crsWkt, out_.tin.crsName = crsName;
  }
  void add(const LodPiece& piece, const ProgressRange&) override {
    const ExtractedLod& part = piece.part;
    for (std::size_t v = 0; v < part.tin.vertices.size(); ++v)
      if (piece.isNew[v]) out_.tin.vertices.push_back(part.tin.vertices[v]), out_.vertexLevel.push_back(part.vertexLevel[v]);
    for (const Triangle& t : part.tin.triangles) out_.tin.triangles.push_back({piece.id[t[0]], piece.id[t[1]], piece.id[t[2]]});
    out_.firstLevel.insert(out_.firstLevel.end(), part.firstLevel.begin(), part.firstLevel.end());
    out_.lastLevel.insert(out_.lastLevel.end(), part.lastLevel.begin(), part.lastLevel.end());
  }
  void setOutline(const std::vector<VertexId>& sharedOutline, std::size_t) override {
    for (VertexId v : sharedOutline) out_.tin.vertices[v].outline = true;
  }

 private:
  ExtractedLod& out_;
};

fs::path temporaryFolder() {
  std::string name = (fs::temp_directory_path() / "tinlod-lod-parts-XXXXXX").string();
  if (!mkdtemp(name.data())) throw Error("cannot make a temporary folder in " + fs::temp_directory_path().string());
  return name;
}

}  // namespace

CatalogueLodRun extractCatalogueLod(const std::string& cataloguePath,
                                    const std::function<LodOptions(const std::string& crsWkt)>& optionsFor,
                                    const fs::path& partsFolder, CatalogueLodSink& sink, const ProgressRange& progress) {
  const std::vector<CatalogueTile> tiles = readCatalogue(cataloguePath);
  requireTileCells(cataloguePath, tiles);
  warnOfUnfinishedTiles(cataloguePath, progress);
  const LodPartFiles parts(partsFolder);
  Hierarchy job;
  const CatalogueLodRun run = extractTiles(tiles, optionsFor, parts, job, progress.sub(0, 0.6));
  sink.start(job.base.crsWkt, job.base.crsName);
  Assembler assembler(sink);
  const ProgressRange writing = progress.sub(0.6, 1);
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    const ProgressRange part = writing.sub(double(i) / tiles.size(), double(i + 1) / tiles.size());
    part.report(0, "Writing tile " + tiles[i].name);
    TileLodPart read = parts.read(i);
    assembler.add(tiles[i], read, part);
  }
  assembler.finish();
  return run;
}

ExtractedLod extractCatalogueLod(const std::string& cataloguePath,
                                 const std::function<LodOptions(const std::string& crsWkt)>& optionsFor,
                                 const ProgressRange& progress) {
  ExtractedLod out;
  MemorySink sink(out);
  const fs::path folder = temporaryFolder();
  CatalogueLodRun run;
  try {
    run = extractCatalogueLod(cataloguePath, optionsFor, folder, sink, progress);
  } catch (...) {
    std::error_code ignored;  // a catalogue refused before its parts' folder was taken over
    fs::remove_all(folder, ignored);
    throw;
  }
  out.levelZeroTriangles = run.levelZeroTriangles;
  out.coarsest = run.coarsest;
  out.seconds = run.seconds;
  out.passes = run.passes;
  return out;
}

}  // namespace tinlod
