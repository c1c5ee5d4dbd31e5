// SPDX-License-Identifier: GPL-3.0-or-later
#include "catalogue_accuracy.h"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <unordered_map>
#include <unordered_set>

#include "accuracy_raster_canvas.h"
#include "catalogue_hierarchy.h"
#include "gdal_handles.h"
#include "release_memory.h"
#include "stored_table.h"
#include "surface_comparison.h"
#include "tile_catalogue.h"
#include "tile_ownership.h"
#include "vertex_place.h"
#include "tinlod/accuracy_report.h"
#include "tinlod/accuracy_statistics.h"
#include "tinlod/dem_reader.h"
#include "tinlod/error.h"
#include "tinlod/height_range.h"
#include "tinlod/tin_rasterizer.h"

namespace tinlod {
namespace {

using Pos = std::array<double, 2>;

// One level's sums over the tiles measured so far: the statistics their builds recorded
// (vertices, triangles, times, certified error) and those of their test points.
struct LevelSums {
  LevelStats stats;
  ErrorStatistics errors;
  MoranAccumulator moran;
  SurfaceComparison surfaces;
};

const HeightRange kAnyHeight{-1e300, 1e300};  // every finite height

// The whole raster's test grid, which every tile's window is a piece of.
struct WholeGrid {
  Dem header;  // the raster's size, georeferencing and CRS, without heights
  CrsTransform toTin;
  TestGrid grid;
  AccuracyOptions options;
  HeightRange valid;
};

WholeGrid wholeGrid(const std::string& demPath, int band, const HeightRange& valid, const std::string& sourceSrs,
                    const std::string& tinCrs, const AccuracyOptions& options, const ProgressRange& progress) {
  // One cell reads the raster's georeferencing (and says what it has to about it once).
  Dem header = readDemWindow(demPath, band, CellWindow{0, 0, 1, 1}, progress, kAnyHeight);  // the tiles count drops
  header.width = header.window.fullWidth, header.height = header.window.fullHeight;
  header.geotransform = header.window.fullGeotransform;
  header.window = RasterWindow{0, 0, header.width, header.height, header.geotransform};
  releaseMemory(header.z);
  const ProgressRange quiet(Feedback{}, 0, 1);  // the sampling run already said what it had to about the CRS
  CrsTransform toTin = CrsTransform::forDem(header, sourceSrs, tinCrs, quiet);
  TestGrid grid = makeTestGrid(header, options.step, toTin);
  if (const std::string small = surfacesMissWarning(grid, options.controlSpacing); !small.empty()) progress.warn(small);
  return WholeGrid{std::move(header), std::move(toTin), std::move(grid), options, valid};
}

int ceilDiv(int a, int b) { return (a + b - 1) / b; }  // a >= 0, b > 0


// The test points of the cells a tile answers for (ownedCells), so that each point counts once.
std::vector<TestRect> ownedPoints(const std::vector<CellRect>& cells, int step) {
  std::vector<TestRect> points;
  for (const CellRect& c : cells) {
    const TestRect p{ceilDiv(c.col0, step), ceilDiv(c.row0, step), ceilDiv(c.col1, step), ceilDiv(c.row1, step)};
    if (!p.empty()) points.push_back(p);
  }
  return points;
}

TestRect boundsOf(const std::vector<TestRect>& rects) {
  TestRect b = rects.front();
  for (const TestRect& r : rects)
    b = {std::min(b.col0, r.col0), std::min(b.row0, r.row0), std::max(b.col1, r.col1), std::max(b.row1, r.row1)};
  return b;
}

// The test points the owned ones need: the 4 x 4 control points of the B-spline about each
// (the control lattice is the whole grid's, so the window starts on it, and within the window
// a surface is the whole grid's) and the right and lower neighbours of Moran's I.
TestRect windowOf(const TestRect& owned, const TestGrid& grid, int spacing) {
  // In 64 bits: a spacing near INT_MAX would overflow.
  const std::int64_t c = spacing;
  const auto start = [&](int first) { return int(std::max<std::int64_t>(0, (first / c - 1) * c)); };
  const auto end = [&](int last, int size) { return int(std::min<std::int64_t>(size, (last / c + 2) * c + 1)); };
  return {start(owned.col0), start(owned.row0), end(owned.col1 - 1, grid.cols), end(owned.row1 - 1, grid.rows)};
}

TestGrid subGrid(const TestGrid& whole, const TestRect& w) {
  TestGrid g = whole;
  g.cols = w.col1 - w.col0, g.rows = w.row1 - w.row0;
  g.geotransform[0] += w.col0 * whole.geotransform[1];
  g.geotransform[3] += w.row0 * whole.geotransform[5];
  g.cellWidth.assign(whole.cellWidth.begin() + w.row0, whole.cellWidth.begin() + w.row1);
  return g;
}

// The window's cells, one test point wider each way, in the TIN's CRS: its edges are
// followed point by point, since a change of CRS bends them.
std::array<double, 4> boxInTinCrs(const WholeGrid& g, const TestRect& w) {
  const double x0 = g.grid.x(w.col0 - 1), x1 = g.grid.x(w.col1), y0 = g.grid.y(w.row0 - 1), y1 = g.grid.y(w.row1);
  constexpr int kSteps = 32;
  std::vector<double> xs, ys;
  for (int k = 0; k <= kSteps; ++k) {
    const double x = x0 + (x1 - x0) * k / kSteps, y = y0 + (y1 - y0) * k / kSteps;
    xs.insert(xs.end(), {x, x, x0, x1});
    ys.insert(ys.end(), {y0, y1, y, y});
  }
  g.toTin.apply(xs, ys);
  std::array<double, 4> box{HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (!std::isfinite(xs[i]) || !std::isfinite(ys[i])) continue;
    box = {std::min(box[0], xs[i]), std::min(box[1], ys[i]), std::max(box[2], xs[i]), std::max(box[3], ys[i])};
  }
  // A hundredth more each way for the bend between the points followed.
  const double dx = (box[2] - box[0]) / 100, dy = (box[3] - box[1]) / 100;
  return {box[0] - dx, box[1] - dy, box[2] + dx, box[3] + dy};
}

bool cellsMeet(const CatalogueTile& tile, const TestRect& w, int step) {
  const int col0 = w.col0 * step, col1 = (w.col1 - 1) * step, row0 = w.row0 * step, row1 = (w.row1 - 1) * step;
  return tile.xoff <= col1 && tile.xoff + tile.xsize - 1 >= col0 && tile.yoff <= row1 && tile.yoff + tile.ysize - 1 >= row0;
}

// Triangles of other tiles: three corners each, with the levels each is in.
struct NeighbourTriangles {
  std::vector<TinVertex> corners;
  std::vector<std::array<std::int32_t, 2>> levels;
};

void readNeighbourTriangles(const CatalogueTile& tile, const std::array<double, 4>& box, std::int32_t coarsest,
                            NeighbourTriangles& out) {
  requireTileFile(tile.name, tile.file);
  const DatasetPtr ds = openReadOnly(tile.file, GDAL_OF_VECTOR);
  if (!ds) throw Error(unreadableTile(tile.name, tile.file, "it is not a GeoPackage GDAL can read"));
  OGRLayer* layer = ds->GetLayerByName("triangles");
  if (!layer) throw Error(unreadableTile(tile.name, tile.file, "it has no triangles layer"));
  const StoredTable table(tile.file, *layer);
  const int first = table.column("first_level"), last = table.column("last_level");
  layer->SetSpatialFilterRect(box[0], box[1], box[2], box[3]);  // through the GeoPackage's R-tree
  struct Read {
    GIntBig fid;
    std::array<TinVertex, 3> corners;
    std::array<std::int32_t, 2> levels;
  };
  std::vector<Read> read;
  for (auto& f : *layer) {
    const StoredRow row(table, *f);
    const auto* polygon = dynamic_cast<const OGRPolygon*>(f->GetGeometryRef());
    const OGRLinearRing* ring = polygon ? polygon->getExteriorRing() : nullptr;
    if (!ring || ring->getNumPoints() < 3) row.damaged("is not a triangle");
    Read t{f->GetFID(), {}, {}};
    for (int k = 0; k < 3; ++k) {
      TinVertex& v = t.corners[k];
      v.x = ring->getX(k), v.y = ring->getY(k), v.z = ring->getZ(k);
    }
    const auto from = static_cast<std::int32_t>(row.integer(first, 0, coarsest, "levels"));
    t.levels = {from, static_cast<std::int32_t>(row.integer(last, from, coarsest, "levels"))};
    read.push_back(t);
  }
  table.checkFullyRead();
  // In id order, as a whole hierarchy of the tiles holds them: where two triangles meet, the
  // rasterizer gives a point on their edge the later one's value, which may differ in the
  // last bit.
  std::sort(read.begin(), read.end(), [](const Read& a, const Read& b) { return a.fid < b.fid; });
  for (const Read& t : read) {
    out.corners.insert(out.corners.end(), t.corners.begin(), t.corners.end());
    out.levels.push_back(t.levels);
  }
}

// The heights of a tile's vertices on its edges, by place: a tile beside it must have the
// same vertex there (the catalogue's tiles made by one job).
class SharedHeights {
 public:
  SharedHeights(const CatalogueTile& tile, const std::vector<TinVertex>& vertices) {
    for (const TinVertex& v : vertices)
      if (v.col == 0 || v.row == 0 || v.col == tile.xsize - 1 || v.row == tile.ysize - 1) heights_[placeOf(v)] = v.z;
  }
  // Throws Error naming `other` when a corner from `first` on lies on one of them at another height.
  void check(const CatalogueTile& other, const std::vector<TinVertex>& corners, std::size_t first) const {
    for (std::size_t k = first; k < corners.size(); ++k) {
      const auto it = heights_.find(placeOf(corners[k]));
      if (it != heights_.end() && it->second != corners[k].z) throw Error(sharedVertexDiffers(other, corners[k]));
    }
  }

 private:
  std::unordered_map<Place, double, PlaceHash> heights_;
};

// A tile's triangle as measured: its corners and the levels it is in (16 bytes, where the
// hierarchy's 28 hold what measuring does not read).
struct MeasuredTriangle {
  Triangle v;
  std::int16_t firstLevel, lastLevel;
};

// One tile's test points, measured level by level on a window of the whole test grid: its
// own triangles and those of the tiles beside it that reach into the window.
class TileMeasure {
 public:
  // `owned`: the test points it answers for (ownedPoints). Takes the tile's vertices and
  // triangles, and frees them (as read, they would stay beside the grids); `coarsest`: its
  // hierarchy's coarsest level.
  TileMeasure(const WholeGrid& g, const std::vector<CatalogueTile>& tiles, std::size_t index, std::int32_t coarsest,
              std::vector<TinVertex>&& vertices, std::vector<HierarchyTriangle>&& triangles,
              const std::vector<TestRect>& owned, const ProgressRange& progress);
  // Every level in turn, into sums[level]; the raster's level into `canvas` too.
  void measureLevels(std::vector<LevelSums>& sums, std::int32_t rasterLevel, AccuracyRasterCanvas* canvas,
                     const ProgressRange& progress) const;
  // With -reference dem: the owned test points whose heights -valid_range made nodata.
  std::size_t droppedHeights() const { return droppedHeights_; }

 private:
  // The corners of the other tiles' triangles that reach into the window (three a triangle).
  std::vector<TinVertex> readNeighbours(const std::vector<CatalogueTile>& tiles, std::size_t index,
                                        const std::vector<TinVertex>& vertices);
  void makeReference(const ProgressRange& progress);
  void measure(std::int32_t level, LevelSums& sums, AccuracyRasterCanvas* canvas, const ProgressRange& progress) const;
  std::vector<Triangle> trianglesOf(std::int32_t level) const;
  Grid rasterize(std::int32_t level, const ProgressRange& progress) const;
  void addErrors(const Grid& simplified, const TestRect& rect, LevelSums& sums, Grid* band, int bandRow0) const;

  const WholeGrid& g_;
  std::int32_t coarsest_;
  std::vector<MeasuredTriangle> triangles_;
  std::size_t vertexCount_ = 0;  // the tile's; the other tiles' corners follow
  TestRect window_;
  std::vector<TestRect> owned_;  // in the window's points
  TestGrid grid_;                // the window's
  std::vector<Pos> positions_;
  std::vector<double> z_;
  std::vector<std::array<std::int32_t, 2>> neighbourLevels_;  // of triangles whose corners follow the tile's vertices
  std::size_t neighboursBefore_ = 0;  // of tiles before this one in the catalogue
  Grid reference_;
  std::unique_ptr<BsplineSurface> referenceSurface_;
  std::size_t droppedHeights_ = 0;
};

TileMeasure::TileMeasure(const WholeGrid& g, const std::vector<CatalogueTile>& tiles, std::size_t index,
                         std::int32_t coarsest, std::vector<TinVertex>&& tileVertices,
                         std::vector<HierarchyTriangle>&& triangles, const std::vector<TestRect>& owned,
                         const ProgressRange& progress)
    : g_(g), coarsest_(coarsest), vertexCount_(tileVertices.size()) {
  window_ = windowOf(boundsOf(owned), g.grid, g.options.controlSpacing);
  for (const TestRect& o : owned)
    owned_.push_back({o.col0 - window_.col0, o.row0 - window_.row0, o.col1 - window_.col0, o.row1 - window_.row0});
  grid_ = subGrid(g.grid, window_);
  triangles_.reserve(triangles.size());
  for (const HierarchyTriangle& t : triangles) triangles_.push_back({t.v, t.firstLevel, t.lastLevel});
  releaseMemory(triangles);
  {
    std::vector<TinVertex> vertices = std::move(tileVertices);
    const std::vector<TinVertex> corners = readNeighbours(tiles, index, vertices);
    vertices.insert(vertices.end(), corners.begin(), corners.end());
    // Placed on the whole grid as a whole run places them, and rasterized there: the same
    // values to the bit, so points on an edge fall alike.
    positions_ = gridPositions(g.grid, g.header, vertices, g.toTin);
    z_.reserve(vertices.size());
    for (const TinVertex& v : vertices) z_.push_back(v.z);
  }  // freed before the reference's grid
  makeReference(progress);
}

std::vector<TinVertex> TileMeasure::readNeighbours(const std::vector<CatalogueTile>& tiles, std::size_t index,
                                                   const std::vector<TinVertex>& vertices) {
  NeighbourTriangles neighbours;
  const std::array<double, 4> box = boxInTinCrs(g_, window_);
  const SharedHeights shared(tiles[index], vertices);
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    if (t == index) {
      neighboursBefore_ = neighbours.levels.size();
    } else if (cellsMeet(tiles[t], window_, g_.grid.step)) {
      const std::size_t first = neighbours.corners.size();
      readNeighbourTriangles(tiles[t], box, coarsest_, neighbours);
      shared.check(tiles[t], neighbours.corners, first);
    }
  }
  neighbourLevels_ = std::move(neighbours.levels);
  return std::move(neighbours.corners);
}

void TileMeasure::makeReference(const ProgressRange& progress) {
  const int step = g_.grid.step;
  if (g_.options.reference == Reference::Dem) {
    const CellWindow cells{window_.col0 * step, window_.row0 * step, (window_.col1 - window_.col0 - 1) * step + 1,
                           (window_.row1 - window_.row0 - 1) * step + 1};
    const ProgressRange quiet(Feedback{}, 0, 1);  // the whole raster's header said it
    // Read as they are and dropped here, so that the heights outside -valid_range are
    // counted at the owned points only (windows overlap): one warning for the raster.
    Dem heights = readDemWindow(g_.header.path, g_.header.band, cells, quiet, kAnyHeight);
    for (const TestRect& o : owned_)
      for (int r = o.row0; r < o.row1; ++r)
        for (int c = o.col0; c < o.col1; ++c) {
          const float z = heights.at(r * step, c * step);
          droppedHeights_ += !std::isnan(z) && !g_.valid.contains(z);
        }
    dropHeightsOutside(heights.z, g_.valid);
    reference_ = demHeights(heights, grid_);
  } else {
    reference_ = rasterize(0, progress);
  }
  referenceSurface_ =
      std::make_unique<BsplineSurface>(reference_, g_.options.controlSpacing, grid_.cellWidth, grid_.cellHeight);
}

// In the order of the tiles read as one hierarchy (see readNeighbourTriangles): the tiles
// before this one in the catalogue, this one, the tiles after it.
std::vector<Triangle> TileMeasure::trianglesOf(std::int32_t level) const {
  const auto inLevel = [level](std::int32_t first, std::int32_t last) { return first <= level && level <= last; };
  // Counted first: grown by doubling, the array would take up to twice its size.
  std::size_t count = 0;
  for (const MeasuredTriangle& t : triangles_) count += inLevel(t.firstLevel, t.lastLevel);
  for (const auto& levels : neighbourLevels_) count += inLevel(levels[0], levels[1]);
  std::vector<Triangle> out;
  out.reserve(count);
  const auto first = static_cast<VertexId>(vertexCount_);
  const auto neighbours = [&](std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t)
      if (inLevel(neighbourLevels_[t][0], neighbourLevels_[t][1])) {
        const auto v = static_cast<VertexId>(first + 3 * t);
        out.push_back({v, v + 1, v + 2});
      }
  };
  neighbours(0, neighboursBefore_);
  for (const MeasuredTriangle& t : triangles_)
    if (inLevel(t.firstLevel, t.lastLevel)) out.push_back(t.v);
  neighbours(neighboursBefore_, neighbourLevels_.size());
  return out;
}

Grid TileMeasure::rasterize(std::int32_t level, const ProgressRange& progress) const {
  return rasterizeTin(positions_, z_, trianglesOf(level), grid_.cols, grid_.rows, progress, window_.col0, window_.row0);
}

// `band`, when given, holds the window's rows from `bandRow0` on.
void TileMeasure::addErrors(const Grid& simplified, const TestRect& rect, LevelSums& sums, Grid* band,
                            int bandRow0) const {
  const auto error = [&](int c, int r) { return simplified.at(c, r) - reference_.at(c, r); };  // NaN unless both
  for (int r = rect.row0; r < rect.row1; ++r)
    for (int c = rect.col0; c < rect.col1; ++c) {
      const double e = error(c, r);
      if (std::isnan(e)) continue;
      const int col = window_.col0 + c, row = window_.row0 + r;  // the whole grid's
      sums.errors.add(e, g_.grid.x(col), g_.grid.y(row), std::uint64_t(row) * g_.grid.cols + col);
      sums.moran.addPoint(e);
      // The pairs with the right and lower neighbours: each pair once, by its first point.
      if (c + 1 < simplified.cols && !std::isnan(error(c + 1, r))) sums.moran.addPair(e, error(c + 1, r));
      if (r + 1 < simplified.rows && !std::isnan(error(c, r + 1))) sums.moran.addPair(e, error(c, r + 1));
      if (band) band->at(c, r - bandRow0) = e;
    }
}

void TileMeasure::measure(std::int32_t level, LevelSums& sums, AccuracyRasterCanvas* canvas,
                          const ProgressRange& progress) const {
  const Grid simplified = rasterize(level, progress.sub(0, 0.3));
  const BsplineSurface surface(simplified, g_.options.controlSpacing, grid_.cellWidth, grid_.cellHeight);
  // A strip of rows at a time, with or without the raster (so the sums are grouped alike):
  // the raster's four bands over a strip, not over the window. Strips end on the whole
  // grid's multiples of kComparedRows, the canvas's block rows, so that each strip writes
  // whole block rows where the window covers them.
  std::size_t rows = 0, done = 0;
  for (const TestRect& o : owned_) rows += o.row1 - o.row0;
  for (const TestRect& o : owned_)
    for (int row0 = o.row0, row1; row0 < o.row1; row0 = row1) {
      row1 = stripEnd(row0, o.row1, window_.row0);
      const TestRect strip{o.col0, row0, o.col1, row1};
      const std::unique_ptr<AccuracyBands> bands =
          canvas ? std::make_unique<AccuracyBands>(blankBands(grid_.cols, row1 - row0)) : nullptr;
      addErrors(simplified, strip, sums, bands ? &bands->elevationDifference : nullptr, row0);
      const double from = 0.35 + 0.65 * done / rows;
      done += row1 - row0;
      sums.surfaces.merge(compareSurfaces(*referenceSurface_, surface, strip, bands.get(), row0,
                                          progress.sub(from, 0.35 + 0.65 * done / rows)));
      if (canvas) canvas->write(*bands, TestRect{o.col0, 0, o.col1, row1 - row0}, window_.col0, window_.row0 + row0);
    }
}

void TileMeasure::measureLevels(std::vector<LevelSums>& sums, std::int32_t rasterLevel, AccuracyRasterCanvas* canvas,
                                const ProgressRange& progress) const {
  const double levels = coarsest_ + 1;
  for (std::int32_t L = 0; L <= coarsest_; ++L)
    measure(L, sums[L], L == rasterLevel ? canvas : nullptr, progress.sub(L / levels, (L + 1) / levels));
}

// Adds vertices by highest level to each level's count (a vertex is in every level up to its highest).
void addVertices(const std::vector<std::size_t>& topLevel, std::vector<LevelSums>& sums) {
  std::size_t above = 0;  // vertices whose highest level is L or more
  for (std::size_t L = sums.size(); L-- > 0;) sums[L].stats.vertices += above += topLevel[L];
}

// The cells on the tiles' edges, gathered across tiles: a vertex on a line two (or, at a
// corner, four) tiles share counts once, whichever of them hold it (beside nodata, only
// one may). A cell is counted, and forgotten, once every finished tile that holds it has
// been read: the map holds the edges of the tiles read but not yet met by their
// neighbours, not every edge of the catalogue.
class EdgeVertices {
 public:
  explicit EdgeVertices(const std::vector<CatalogueTile>& finished) {
    for (const CatalogueTile& t : finished) {
      starts_.insert(key(t.yoff, t.xoff));
      cols_.emplace(t.xoff, t.xsize), rows_.emplace(t.yoff, t.ysize);
    }
  }

  // A tile's vertex on its edge, by cell of the raster, with its highest level: counted in
  // topLevel once the last of the cell's tiles has given it.
  void add(int row, int col, std::int32_t level, std::vector<std::size_t>& topLevel) {
    const std::uint64_t cell = key(row, col);
    Seen& seen = cells_[cell];
    seen.level = std::max(seen.level, level), ++seen.tiles;
    if (seen.tiles >= holders(row, col)) ++topLevel[std::size_t(seen.level)], cells_.erase(cell);
  }

  // The cells some holder of which had no vertex there (nodata on its side).
  void finish(std::vector<std::size_t>& topLevel) {
    for (const auto& [cell, seen] : cells_) ++topLevel[std::size_t(seen.level)];
    cells_.clear();
  }

 private:
  struct Seen {
    std::int32_t level = 0;
    int tiles = 0;
  };
  static std::uint64_t key(int row, int col) { return (std::uint64_t(std::uint32_t(row)) << 32) | std::uint32_t(col); }

  // The finished tiles whose window holds the cell.
  int holders(int row, int col) const {
    int n = 0;
    for (int xoff : starts(cols_, col))
      for (int yoff : starts(rows_, row)) n += starts_.count(key(yoff, xoff)) > 0;
    return n;
  }

  // The starts of the windows (start: size) that hold a position: at most two.
  static std::vector<int> starts(const std::map<int, int>& windows, int at) {
    std::vector<int> out;
    auto it = windows.upper_bound(at);
    for (int k = 0; k < 2 && it != windows.begin(); ++k) {
      --it;
      if (at < it->first + it->second) out.push_back(it->first);
    }
    return out;
  }

  std::unordered_set<std::uint64_t> starts_;  // (yoff, xoff) of the finished tiles
  std::map<int, int> cols_, rows_;            // the windows' starts and sizes across and down
  std::unordered_map<std::uint64_t, Seen> cells_;
};

// The level statistics the build recorded, pooled as readCatalogueHierarchy pools them,
// and the tile's vertices by their highest level, those on its edges through `edges`.
void poolLevels(const CatalogueTile& tile, const Hierarchy& h, std::vector<LevelSums>& sums, EdgeVertices& edges) {
  for (std::size_t L = 0; L < sums.size(); ++L) poolLevelStats(sums[L].stats, h.levels[L]);
  std::vector<std::size_t> topLevel(sums.size(), 0);
  for (std::size_t v = 0; v < h.base.vertices.size(); ++v) {
    const TinVertex& p = h.base.vertices[v];
    if (p.col == 0 || p.row == 0 || p.col == tile.xsize - 1 || p.row == tile.ysize - 1)
      edges.add(p.row + tile.yoff, p.col + tile.xoff, h.vertexLevel[v], topLevel);
    else
      ++topLevel[h.vertexLevel[v]];
  }
  addVertices(topLevel, sums);
}

void addEdgeVertices(EdgeVertices& edges, std::vector<LevelSums>& sums) {
  std::vector<std::size_t> topLevel(sums.size(), 0);
  edges.finish(topLevel);
  addVertices(topLevel, sums);
}

LevelAccuracy rowOf(const LevelSums& s, const Hierarchy& job, const std::string& dem, std::int32_t level) {
  LevelAccuracy row = levelRow(job, dem, level, s.stats);
  row.testPoints = s.errors.count();
  row.rmse = s.errors.rmse(), row.meanError = s.errors.mean(), row.maxAbsError = s.errors.maxAbs();
  row.maxErrorX = s.errors.maxX(), row.maxErrorY = s.errors.maxY();
  row.moransI = s.moran.value();
  row.variables = s.surfaces.describe();
  return row;
}

// Tiles cut from another raster would be measured outside the DEM.
void checkTilesFit(const std::vector<CatalogueTile>& tiles, const Dem& raster) {
  for (const CatalogueTile& t : tiles)
    if (t.xoff < 0 || t.yoff < 0 || std::int64_t{t.xoff} + t.xsize > raster.width ||
        std::int64_t{t.yoff} + t.ysize > raster.height)
      throw Error("'" + raster.path + "' is " + std::to_string(raster.width) + " x " + std::to_string(raster.height) +
                  " cells, but tile " + t.name + " of the catalogue holds columns " + std::to_string(t.xoff) + " to " +
                  std::to_string(std::int64_t{t.xoff} + t.xsize - 1) + ", rows " + std::to_string(t.yoff) + " to " +
                  std::to_string(std::int64_t{t.yoff} + t.ysize - 1) + ": give the DEM the tiles were cut from");
}

// The cells of the tiles not finished, which no finished tile holds: no triangle covers
// them, but the reference's surface may reach them (the DEM's, or level 0's near its
// edge), and a whole run writes its curvature (band 3) there and counts a point wherever
// both surfaces reach. Each such tile is measured as a tile without triangles, at every
// level: its neighbours' triangles reach into its window as they would read as one.
// `parts(m)`: the progress of missing tile m. Returns the test points whose heights
// -valid_range dropped.
template <class Parts>
std::size_t measureMissingTiles(const WholeGrid& g, const std::vector<CatalogueTile>& tiles,
                                const std::vector<CatalogueTile>& missing, std::int32_t coarsest, std::int32_t rasterLevel,
                                std::vector<LevelSums>& sums, AccuracyRasterCanvas* canvas, const Parts& parts) {
  std::size_t dropped = 0;
  std::vector<CatalogueTile> withIt = tiles;
  withIt.emplace_back();  // the missing tile measured, last: after every finished tile, as read as one
  for (std::size_t m = 0; m < missing.size(); ++m) {
    const std::vector<TestRect> owned = ownedPoints(cellsLeftBy(tiles, missing, m), g.grid.step);
    if (owned.empty()) continue;
    const ProgressRange part = parts(m);
    part.report(0, "Measuring the cells of unfinished tile " + missing[m].name);
    withIt.back() = missing[m];
    const TileMeasure measure(g, withIt, tiles.size(), coarsest, {}, {}, owned, part.sub(0, 0.1));
    dropped += measure.droppedHeights();
    measure.measureLevels(sums, rasterLevel, canvas, part.sub(0.1, 1));
  }
  return dropped;
}

}  // namespace

void requireTestPoints(const std::vector<LevelAccuracy>& rows, const std::string& demPath) {
  const std::size_t points = rows.empty() ? 0 : rows.front().testPoints;
  if (points == 0) throw Error("no test point of '" + demPath + "' lies on the TIN: give the DEM the TIN was made from");
  if (points < std::size_t{kFewestTestPoints})
    throw Error("only " + std::to_string(points) + " test point" + (points == 1 ? "" : "s") + " of '" + demPath +
                (points == 1 ? "' lies" : "' lie") + " on the TIN: give the DEM the TIN was made from, or a smaller -step");
}

AccuracyReport measureCatalogue(const std::string& demPath, const std::string& cataloguePath, int band,
                                const HeightRange& validHeights, const std::string& sourceSrs,
                                const AccuracyOutputs& outputs, const AccuracyFiles& files, const ProgressRange& progress) {
  const std::vector<CatalogueTile> tiles = readCatalogue(cataloguePath);
  requireTileCells(cataloguePath, tiles);
  const std::vector<CatalogueTile> missing = readUnfinishedTiles(cataloguePath);
  warnOfUnfinishedTiles(cataloguePath, progress);
  // The finished tiles, then the cells only unfinished ones hold, each tile a share.
  const double shares = double(tiles.size() + missing.size());
  const auto partOf = [&](std::size_t k) { return progress.sub(0.95 * k / shares, 0.95 * (k + 1) / shares); };
  std::unique_ptr<WholeGrid> g;
  Hierarchy job;
  std::vector<LevelSums> sums;
  std::unique_ptr<AccuracyRasterCanvas> canvas;
  std::int32_t rasterLevel = 0;
  std::size_t droppedHeights = 0;
  EdgeVertices edges(tiles);
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    const CatalogueTile& tile = tiles[i];
    const ProgressRange part = partOf(i);
    part.report(0, "Measuring tile " + tile.name + " (" + std::to_string(i + 1) + " of " + std::to_string(tiles.size()) + ")");
    StoredHierarchy stored = readCatalogueTile(tile, part.sub(0, 0.2));
    // Levels are measured from the triangles alone: the groups and their links (a tenth of
    // a tile's hierarchy), and level 0 again as a TIN, need not stay beside the grids.
    releaseMemory(stored.hierarchy.groups), releaseMemory(stored.hierarchy.links), releaseMemory(stored.hierarchy.rings);
    releaseMemory(stored.hierarchy.base.triangles);
    Hierarchy& h = stored.hierarchy;
    if (i == 0) {
      rasterLevel = outputs.rasterLevel < 0 ? h.coarsest() : outputs.rasterLevel;
      if (rasterLevel > h.coarsest())
        throw Error("-level " + std::to_string(outputs.rasterLevel) + " does not exist: the hierarchy has levels 0 to " +
                    std::to_string(h.coarsest()));
      g = std::make_unique<WholeGrid>(
          wholeGrid(demPath, band, validHeights, sourceSrs, h.base.crsWkt, outputs.options, part.sub(0.2, 0.25)));
      checkTilesFit(tiles, g->header);
      checkTilesFit(missing, g->header);
      job = jobOf(h);
      sums.resize(h.levels.size());
      if (files.raster) canvas = std::make_unique<AccuracyRasterCanvas>(g->grid, *files.raster, outputs.raster);
    } else {
      checkSameJob(tile, h, job);
    }
    const std::vector<CellRect> cells = ownedCells(tiles, i);
    poolLevels(tile, h, sums, edges);
    const std::vector<TestRect> owned = ownedPoints(cells, g->grid.step);
    if (owned.empty()) continue;
    const TileMeasure measure(*g, tiles, i, h.coarsest(), std::move(h.base.vertices), std::move(h.triangles), owned,
                              part.sub(0.25, 0.3));
    releaseFreedMemory();  // what reading the tile left in glibc's heaps, resident beside the grids
    droppedHeights += measure.droppedHeights();
    measure.measureLevels(sums, rasterLevel, canvas.get(), part.sub(0.3, 1));
  }
  addEdgeVertices(edges, sums);
  droppedHeights += measureMissingTiles(*g, tiles, missing, job.coarsest(), rasterLevel, sums, canvas.get(),
                                        [&](std::size_t m) { return partOf(tiles.size() + m); });
  if (droppedHeights > 0)
    progress.warn("ignored " + std::to_string(droppedHeights) + (droppedHeights == 1 ? " test point" : " test points") +
                  " of '" + demPath + "' with heights outside " + validHeights.text() +
                  " (treated as nodata); widen with -valid_range");
  std::vector<LevelAccuracy> rows;
  for (std::size_t L = 0; L < sums.size(); ++L) rows.push_back(rowOf(sums[L], job, demName(demPath), std::int32_t(L)));
  requireTestPoints(rows, demPath);
  // A report of some tiles only says so wherever it is read later.
  const std::string unfinished = unfinishedTiles(cataloguePath);
  AccuracyReport report = makeReport(outputs.options,
                                     "Accuracy of the TIN hierarchy of " + demName(demPath) +
                                         (unfinished.empty() ? "" : " (" + unfinished + ": the finished tiles alone)"),
                                     crsNameOf(g->grid.crsWkt), std::move(rows));
  if (canvas) canvas->finish(progress.sub(0.95, 0.99));
  if (files.report) writeAccuracyReport(report, *files.report);
  return report;
}

}  // namespace tinlod
