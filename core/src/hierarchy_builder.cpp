// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/hierarchy_builder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

#include "border_lines.h"
#include "cell_errors.h"
#include "compact_in_place.h"
#include "nearest_vertices.h"
#include "outline_chain.h"
#include "parallel_blocks.h"
#include "radix_sort.h"
#include "release_memory.h"
#include "simplification_mesh.h"
#include "text_and_paths.h"
#include "vertex_rings.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

using Clock = std::chrono::steady_clock;

// Not yet replaced (a triangle) or deleted (a vertex): above every level there may be.
constexpr std::int32_t kOpenLevel = std::numeric_limits<std::int16_t>::max();
static_assert(kOpenLevel > kMaxLevel, "an open level must lie above every level");
constexpr std::size_t kMinLevelShare = 100;  // a level must delete at least 1 / 100 of its vertices

double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

// A vertex chosen for deletion, and where its parts of the level's arrays start.
struct Pick {
  double importance;
  VertexId id;
  std::uint32_t degree;  // ring vertices
  bool open = false;     // on the outline: degree - 1 triangles around it, not degree
  std::size_t fill = 0;  // its degree - 2 new triangles, in fill_ and new triangle ids
  std::size_t ring = 0;  // its degree ring vertices, slots and outer triangles
  std::uint32_t triangles() const { return open ? degree - 1 : degree; }
};

// With one threshold per level: the candidates from `bottom` up (the threshold's survey
// bin) of which at most `picks` may go.
struct TieQuota {
  double bottom = INFINITY;
  std::size_t picks = SIZE_MAX;
};

// Deletes independent sets of vertices level by level from level 0, recording the
// hierarchy. The stars of an independent set are disjoint, so each level is done on
// every core in two passes: one plans every deletion and records it in the hierarchy
// (reading the mesh only), the other changes the mesh. Every count is known once the
// set is chosen, so each deletion writes its own ranges of the hierarchy's arrays.
class Simplifier {
 public:
  Simplifier(Tin base, const Dem& dem, std::vector<std::uint8_t> fixed, const HierarchyOptions& options,
             const ProgressRange& progress, const TileBorders* tile)
      : options_(options), progress_(progress), dem_(dem), tile_(tile) {
    h_.base = std::move(base);
    h_.options = options;
    h_.fixed = std::move(fixed);
    h_.fixed.resize(h_.base.vertices.size(), 0);
    original_ = h_.base.vertices.size();
    stopCount_ = static_cast<std::size_t>(std::ceil(options_.stopPct / 100.0 * original_));
    // The other core writes the simplifier's own arrays meanwhile: first touching their
    // memory (80 MB on alps_2x2) takes a core some hundredths of a second.
    runBoth([&] { mesh_ = SimplificationMesh(h_.base); }, [&] { allocate(); });
    releaseMemory(h_.base.neighbours);  // the mesh has them now
    if (tile_) borders_ = BorderLines(h_.base, dem_, *tile_);
  }

  Hierarchy run(const std::vector<PointXY>& keep) {
    current_ = original_;
    triangles_ = h_.base.triangles.size();
    setUp(keep);
    h_.levels.push_back(levelStats(0, 0, 0, 0));
    // A survey writes no triangle errors and no level's figures: past level 0 (the cell
    // size), its triangles are not measured against the DEM, which no selection reads.
    if (!records_) releaseMemory(slotCells_);
    while (tile_ ? h_.coarsest() < tile_->levels : current_ > stopCount_) {
      if (!tile_ && options_.maxLevels > 0 && h_.coarsest() >= options_.maxLevels) {
        h_.stopReason = "-max_levels " + std::to_string(options_.maxLevels) + " reached";
        break;
      }
      if (h_.coarsest() >= kMaxLevel) {
        h_.stopReason = "a hierarchy holds at most " + std::to_string(kMaxLevel + 1) + " levels";
        break;
      }
      const std::int32_t level = h_.coarsest() + 1;
      const Clock::time_point t0 = Clock::now();
      std::vector<Pick> picks = select(level);
      const Clock::time_point t1 = Clock::now();
      // A level that deletes almost nothing only adds a layer: the rest is fixed, or (threshold
      // mode) above the threshold. 1 % is rounded down, so that a TIN of under 200 vertices
      // may still lose one. A tile makes every level, as its neighbours do.
      if (!tile_ && (picks.empty() || picks.size() < current_ / kMinLevelShare)) {
        // Cut short by the target itself, the level would have reached it: the build stops
        // within 1 % of the target, and the rest could go (zion at -stop_pct 13.35 was told
        // its fixed and outline vertices were why, with over 3,000 inner ones left).
        const bool reachesTarget = !picks.empty() && current_ - picks.size() <= stopCount_;
        if (!reachesTarget) h_.stopReason = whyStopped(picks.size());
        break;
      }
      deleteAll(picks, level);
      const Clock::time_point t2 = Clock::now();
      current_ -= picks.size();
      h_.levels.push_back(levelStats(level, picks.size(), seconds(t0, t1), seconds(t1, t2)));
      reportProgress(level, 1, 0);  // the level just made: the next is named when its selection starts
    }
    finish();
    return std::move(h_);
  }

 private:
  // Where a level's records start (or end) in the hierarchy's arrays.
  struct Ranges {
    std::size_t group, triangles, rings;
  };

  // Reads only the base TIN, so it may run while the mesh is built.
  void allocate() {
    const std::size_t nv = h_.base.vertices.size(), slots = h_.base.triangles.size();
    if (records_) {
      reserveForDeletions();
      for (const Triangle& tri : h_.base.triangles) {
        HierarchyTriangle ht;
        ht.v = tri;
        ht.lastLevel = kOpenLevel;
        h_.triangles.push_back(ht);
      }
    }
    used_ = {0, h_.base.triangles.size(), 0};
    slotCells_.assign(slots, TriangleCells{});
    h_.vertexLevel.assign(nv, kOpenLevel);
    importance_.assign(nv, 0.0);
    stamp_.assign(nv, -1);
    stale_.assign(nv, 1);
    rings_.reset(nv);
  }

  void setUp(const std::vector<PointXY>& keep) {
    const std::size_t nv = h_.base.vertices.size();
    fixNearest(keep);
    cells_ = CellErrors(dem_, h_.base);
    if (options_.measure == Measure::Error) cells_.bound(options_.maxError);
    measureLevelZero();
    outline_ = OutlineChain(mesh_, h_.base, dem_);
    // Outline vertices go only as OutlineChain allows; a raster corner, a vertex where two
    // parts of the TIN touch, and every outline vertex with -keep_outline stay.
    for (VertexId v = 0; v < nv; ++v) {
      if (onBorder(v)) {
        // Only the border rule, which both tiles apply alike, says whether a border vertex
        // stays (a line's peaks and pits among its pinned cells, read beyond the tile):
        // not the peaks, pits or points to keep this tile sees alone.
        h_.fixed[v] = tile_->pinned[v];
      } else if (mesh_.open(v) && (options_.keepOutline || !mesh_.deletableOpen(v) || outline_.rasterCorner(v))) {
        h_.fixed[v] = 1;
      }
      if (!h_.fixed[v] && !onBorder(v)) live_.push_back(v);
      outlineLeft_ += mesh_.open(v) && mesh_.inTriangle(v);
    }
    // The outline may move by one cell at level 1 unless told otherwise: a cell's size is
    // the TIN's area over the cells it covers.
    std::int64_t covered = 0;
    for (const TriangleCells& c : slotCells_) covered += c.cells;
    cellSize_ = covered > 0 ? std::sqrt(totalArea(h_.base) / double(covered)) : 0;
    tolerance_ = std::isnan(options_.outlineTolerance) ? cellSize_ : options_.outlineTolerance;
    // Level 0's triangles are also the hierarchy's first ones (and the mesh's): held once
    // while the simplification runs, they are put back when it is done.
    releaseMemory(h_.base.triangles);
  }

  bool onBorder(VertexId v) const { return tile_ && tile_->side[v] >= 0; }

  // Whether a and b lie on the same shared border line. An outline vertex (of a hole that
  // reaches the line) may not go if its new outline edge would run along the line: it would
  // pass over line cells this tile left out, which the other tile has.
  bool onOneBorderLine(VertexId a, VertexId b) const {
    if (!tile_) return false;
    const TinVertex &p = h_.base.vertices[a], &q = h_.base.vertices[b];
    return onOneSharedLine(dem_, p.row, p.col, q.row, q.col);
  }

  // Every triangle of level 0 against the DEM, on every core.
  void measureLevelZero() {
    forEachBlock(static_cast<int>(mesh_.slots()), [&](int begin, int end) {
      for (int slot = begin; slot < end; ++slot) {
        const bool outline[3] = {mesh_.across(slot, 0) == kNoTriangle, mesh_.across(slot, 1) == kNoTriangle,
                                 mesh_.across(slot, 2) == kNoTriangle};
        slotCells_[slot] = cells_.measure(mesh_.corner(slot, 0), mesh_.corner(slot, 1), mesh_.corner(slot, 2), outline, true);
        if (records_) h_.triangles[mesh_.triangleId(slot)].error = roundedUpError(slotCells_[slot].maxError);
      }
    }, [&](double f) { progress_.report(0.1 * f, "Measuring level 0 against the DEM"); });
  }

  // Every deletion adds to the hierarchy's arrays. Reserved once, for as many deletions
  // as the run may make at a generous mean degree, they are not copied level after level
  // as they grow; reserve that is never written takes address space, not memory.
  // A tile makes a set number of levels, whatever their counts: it may delete them all.
  std::size_t maxDeletions() const { return tile_ ? original_ : original_ - std::min(original_, stopCount_); }

  void reserveForDeletions() {
    constexpr std::size_t kMeanDegree = 7;
    const std::size_t deletions = maxDeletions();
    h_.triangles.reserve(h_.base.triangles.size() + deletions * (kMeanDegree - 2));
    h_.rings.reserve(deletions * kMeanDegree);
    h_.groups.reserve(deletions);
  }

  // Each point keeps the vertex nearest to it, if it falls on the TIN's data.
  // In a tile, a point holds its nearest vertex off the tile's shared lines: the border
  // rule alone, which both tiles apply alike, decides the vertices on them. A point beyond
  // the tile's vertices is another tile's, not off the data.
  void fixNearest(const std::vector<PointXY>& keep) {
    std::vector<PointXY> mine = keep;
    std::vector<std::uint8_t> onLines;
    if (tile_) {
      onLines.assign(h_.base.vertices.size(), 0);
      for (VertexId v = 0; v < onLines.size(); ++v) onLines[v] = onBorder(v);
      double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
      for (const TinVertex& v : h_.base.vertices) {
        x0 = std::min(x0, v.x), y0 = std::min(y0, v.y);
        x1 = std::max(x1, v.x), y1 = std::max(y1, v.y);
      }
      const auto beyond = [&](const PointXY& p) { return p[0] < x0 || p[0] > x1 || p[1] < y0 || p[1] > y1; };
      mine.erase(std::remove_if(mine.begin(), mine.end(), beyond), mine.end());
    }
    std::size_t off = 0;
    for (VertexId v : nearestVerticesOnData(h_.base, mine, off, progress_.sub(0, 0.1), onLines)) h_.fixed[v] = 1;
    if (off > 0)
      progress_.warn(std::to_string(off) + " of the " + std::to_string(mine.size()) + " points to keep" +
                     (tile_ ? " within the tile's extent" : "") +
                     " fall outside the TIN and were ignored: over nodata, or between the raster's edge and its "
                     "outermost cell centres, where the TIN's outline runs");
  }

  bool eligible(VertexId v) const {
    return options_.measure != Measure::Degree || mesh_.degree(v) <= options_.maxDegree;
  }

  // A thread's scratch for one star's walk.
  struct StarScratch {
    Star star;
    std::vector<VertexId> ring;
    std::vector<std::int32_t> slots, outer;
    std::vector<LocalTriangle> fill;

    void walk(const SimplificationMesh& mesh, VertexId v) {
      const std::size_t d = static_cast<std::size_t>(mesh.degree(v));
      ring.resize(d), slots.resize(d), outer.resize(d);
      mesh.starOf(v, ring.data(), slots.data(), outer.data(), star);
    }
  };

  // Whether the new triangle's edge opposite corner e is on the outline: a ring edge with
  // nothing beyond (the new outline edge of an open star included).
  static void outlineEdges(const LocalTriangle& t, int degree, const std::int32_t* outer, bool (&outline)[3]) {
    for (int e = 0; e < 3; ++e) {
      const int p = t[(e + 1) % 3], q = t[(e + 2) % 3];
      outline[e] = q == (p + 1) % degree && outer[p] == kNoTriangle;
    }
  }

  TriangleCells measureFill(const VertexId* ring, const std::int32_t* outer, int degree, const LocalTriangle& t) {
    bool outline[3];
    outlineEdges(t, degree, outer, outline);
    return cells_.measure(ring[t[0]], ring[t[1]], ring[t[2]], outline);
  }

  // The error measure on the star's fill (s.fill): the largest distance to the DEM at the
  // valid cells under its new triangles; +infinity when a cell would pass its bound.
  double cellError(StarScratch& s) {
    TriangleCells all;
    const int d = static_cast<int>(s.ring.size());
    for (const LocalTriangle& t : s.fill) all.add(measureFill(s.ring.data(), s.outer.data(), d, t));
    return cells_.bounded() && all.excess > 0 ? INFINITY : all.maxError;
  }

  // An open star's fill is the constrained Delaunay triangulation of its polygon; where the
  // new outline edge runs outside the TIN, the triangle beyond a ring edge can have its
  // apex in a fill triangle's circle (the old outline hid it). Such a fill would leave the
  // level no longer Delaunay, so the vertex stays (exact in-circle).
  bool fillMeetsItsNeighbours(const StarScratch& s) const {
    const int d = static_cast<int>(s.ring.size());
    thread_local std::vector<int> onEdge;
    onEdge.resize(d);
    ringEdgeTriangles(s.fill.data(), d, onEdge.data());
    for (int k = 0; k + 1 < d; ++k) {
      const std::int32_t beyond = s.outer[k];
      if (beyond == kNoTriangle) continue;
      VertexId apex = 0;
      for (int c = 0; c < 3; ++c) {
        const VertexId w = mesh_.corner(beyond, c);
        if (w != s.ring[k] && w != s.ring[k + 1]) apex = w;
      }
      const LocalTriangle& t = s.fill[onEdge[k]];
      if (strictlyInCircle(s.star.ring[t[0]], s.star.ring[t[1]], s.star.ring[t[2]], mesh_.point(apex))) return false;
    }
    return true;
  }

  // How far the outline may move in the level being made: the tolerance at level 1,
  // growing as the spacing of the vertices left does.
  double outlineTolerance() const { return tolerance_ * std::sqrt(double(original_) / double(std::max<std::size_t>(current_, 1))); }

  // Only reads the mesh and writes the vertex's own entry: safe in parallel.
  void updateImportance(VertexId v, StarScratch& s) {
    rings_.setDegree(v, mesh_.geometryOf(v, s.star, rings_.place(v), VertexRings::kCapacity));
    stale_[v] = 0;
    const bool open = mesh_.open(v);
    if (!open && options_.measure != Measure::Error) {
      importance_[v] = importance(options_.measure, s.star);
      return;
    }
    // The exact fill, made once: the outline's checks and the error or volume read it.
    s.walk(mesh_, v);
    if (!retriangulateStar(s.star, s.fill) || (open && onOneBorderLine(s.ring.front(), s.ring.back())) ||
        (open && (!outline_.allows(mesh_, v, s.star, s.ring.front(), s.ring.back(), outlineTolerance(), 0.5 * cellSize_,
                                   [&](VertexId u) { return h_.vertexLevel[u] != kOpenLevel; }) ||
                  !fillMeetsItsNeighbours(s)))) {
      importance_[v] = INFINITY;
      return;
    }
    if (options_.measure == Measure::Error) importance_[v] = cellError(s);
    else if (options_.measure == Measure::Volume) importance_[v] = volumeChange(s.star, s.fill);
    else importance_[v] = importance(options_.measure, s.star);
  }

  // Importances change only around deleted vertices; those are recomputed at the start of
  // each level, split over the machine's cores (a cancel stops every thread). An outline
  // vertex is measured again at every level, as the outline's tolerance grows.
  void updateStaleImportances(std::int32_t level) {
    std::vector<VertexId> stale;
    for (VertexId v : live_)
      if ((stale_[v] || mesh_.open(v)) && eligible(v)) stale.push_back(v);
    const std::string phase = "Selecting level " + std::to_string(level);
    // Named before the work: the calling thread reports between its own blocks, and on a
    // busy machine the other threads may take them all.
    progress_.report(lastFraction_, phase);
    forEachBlock(static_cast<int>(stale.size()), [&](int begin, int end) {
      StarScratch scratch;
      for (int i = begin; i < end; ++i) {
        mesh_.prefetchAhead(i, end, [&](int j) { return stale[j]; });
        updateImportance(stale[i], scratch);
      }
    }, [&](double) { progress_.report(lastFraction_, phase); });
  }

  bool wanted(double importance) const {
    if (!(importance < INFINITY)) return false;
    if (!options_.levelThresholds.empty()) return importance < levelThreshold_;
    return !options_.thresholdMode || importance < options_.threshold;
  }

  // After each level, so the next walks stars that lie side by side. The triangles'
  // figures follow them to the compacted slots, moved in place beside the mesh's, on a
  // thread of their own.
  void compact() {
    const Compaction& slots = mesh_.planCompaction();
    runBoth([&] { mesh_.applyCompaction(); }, [&] { if (records_) compactInPlace(slotCells_, slots); });
    mesh_.endCompaction();
  }

  // Best first, ties broken by vertex id (the candidates are listed by id and the sort is
  // stable): the result never depends on memory layout.
  // Each pick blocks its neighbours, so the set is independent. Returned in vertex order,
  // which is the TIN's spatial order: the plan and the mesh are then walked in cache.
  std::vector<Pick> select(std::int32_t level) {
    const bool scheduled = !options_.levelThresholds.empty();
    if (scheduled) levelThreshold_ = options_.levelThresholds[std::min<std::size_t>(level, options_.levelThresholds.size()) - 1];
    updateStaleImportances(level);
    sortCandidates();
    std::size_t limit = current_ > stopCount_ ? current_ - stopCount_ : 0;
    if (scheduled) limit = current_;  // the raster's threshold, not this tile's share, says how many
    else if (!options_.thresholdMode)
      limit = std::min(limit, static_cast<std::size_t>(std::floor(options_.deletePct / 100.0 * current_)));
    tieQuota_ = scheduled ? tieQuota(level) : TieQuota{};
    std::vector<Pick> picks;
    if (tile_) {
      pickBorders(level, picks);
      limit += picks.size();  // the border's own share: its rule, not the tile's, says how many
    }
    // The pick runs on one core; the other meanwhile writes the memory the hierarchy's
    // arrays will grow into, for as many picks as the last level made and a tenth more
    // (an independent set rarely holds more than a quarter of the vertices): never the
    // whole run's reserve at once.
    const std::size_t expected = std::min(limit, lastPicks_ > 0 ? lastPicks_ + lastPicks_ / 10 : current_ / 4);
    const std::size_t borderPicks = picks.size();
    runBoth([&] { pickBestFirst(limit, level, picks); },
            [&] { growHierarchy(expectedGrowth(expected), false); });
    if (options_.survey) survey(level, picks, borderPicks);
    // Made anew next level: held through the deletion, they would add to its peak (30 MB
    // at level 1 of a 4096 x 4096 tile).
    releaseMemory(candidates_[0]), releaseMemory(candidates_[1]);
    std::vector<Pick> scratch;
    radixSort(picks, [](const Pick& p) { return std::uint64_t{p.id}; }, scratch);
    std::size_t fills = 0, rings = 0;
    for (Pick& p : picks) {
      p.fill = fills, p.ring = rings;
      fills += p.degree - 2, rings += p.degree;
    }
    fill_.resize(fills), slots_.resize(rings), outer_.resize(rings);
    return picks;
  }

  // Resizes an array, giving back its memory when it uses under two thirds of it (as
  // growing by doubling may leave it) while the hierarchy's arrays grow.
  template <class T>
  static void fitted(std::vector<T>& v, std::size_t n) {
    v.resize(n);
    if (3 * n < 2 * v.capacity()) v.shrink_to_fit();
  }

  // How many of the level's candidates in its threshold's survey bin may go: its share of
  // them (a flat area's ties), whatever independence blocks among them on the way. Those
  // below the bin all may. A share of the picks, not of the candidates gone through: how
  // many of a flat area's ties its neighbours block depends on what earlier levels left.
  TieQuota tieQuota(std::int32_t level) const {
    const std::size_t k = std::min<std::size_t>(level, options_.levelThresholds.size()) - 1;
    const double share = k < options_.levelShares.size() ? options_.levelShares[k] : 1.0;
    if (share >= 1) return {};
    const double bottom = surveyBinBottom(levelThreshold_);
    std::size_t inBin = 0;
    for (const std::vector<Candidate>& half : candidates_)
      for (const Candidate& c : half) inBin += c.first >= bottom;
    return {bottom, static_cast<std::size_t>(std::floor(share * double(inBin)))};
  }

  // The level's candidates by importance, and how many of them the pick went through to
  // take its picks (the others it met were blocked by a neighbour's pick): that share is
  // what independence lets through, whatever stopped the pick.
  void survey(std::int32_t level, const std::vector<Pick>& picks, std::size_t borderPicks) {
    LevelSurvey l;
    l.level = level;
    l.vertices = current_;
    l.picked = picks.size() - borderPicks;
    l.last = l.picked ? picks.back().importance : 0;
    l.considered = stoppedAt_.first + stoppedAt_.second;
    l.histogram.assign(kSurveyBins, 0);
    for (const std::vector<Candidate>& half : candidates_)
      for (const Candidate& c : half) ++l.histogram[surveyBin(c.first)];
    l.pickedHistogram.assign(kSurveyBins, 0);
    for (std::size_t k = borderPicks; k < picks.size(); ++k) ++l.pickedHistogram[surveyBin(picks[k].importance)];
    if (options_.levelThresholds.empty()) l.walkHistogram = walkOn(level, l.pickedHistogram);
    countAsTheUnion(l, picks, borderPicks);
    h_.survey.push_back(std::move(l));
  }

  // The level's vertices and the border rule's picks as a job's union counts them. Only
  // border vertices are shared with another tile: each counts its share less than 1. The
  // border picks go beside the tile's own: the driver's thresholds leave room for them, or
  // every level would delete them on top of its share.
  void countAsTheUnion(LevelSurvey& l, const std::vector<Pick>& picks, std::size_t borderPicks) const {
    l.unionVertices = double(current_);
    l.borderPicked = double(borderPicks);
    if (!tile_) return;
    const std::array<bool, 4> shared = sharedSides(dem_);
    for (VertexId v = 0; v < static_cast<VertexId>(h_.vertexLevel.size()); ++v)
      if (onBorder(v) && h_.vertexLevel[v] == kOpenLevel) l.unionVertices -= 1 - unionShare(shared, dem_, h_.base.vertices[v]);
    l.borderPicked = 0;
    for (std::size_t k = 0; k < borderPicks; ++k) l.borderPicked += unionShare(shared, dem_, h_.base.vertices[picks[k].id]);
  }

  // With the raster's volume threshold for the level, a line keeps its vertices where the
  // terrain needs them, as the interior does; otherwise it thins by count. Under a bound,
  // a cell goes only if it is itself within the bound of the line between its neighbours
  // (both tiles interpolate it along that line), and below the level's error threshold
  // (its deviation is the least its error can be): the rounds of agreement then refuse
  // only what cells off the line forbid.
  BorderLines::Limit borderLimit(bool bounded) const {
    const bool scheduled = !options_.levelThresholds.empty();
    if (bounded)
      return {BorderLines::Limit::kDeviation, scheduled ? std::min(options_.maxError, levelThreshold_) : options_.maxError};
    if (options_.measure == Measure::Volume && scheduled) return {BorderLines::Limit::kVolume, levelThreshold_};
    return {};
  }

  // Whether deleting the border vertex keeps every cell of this tile under its new
  // triangles within the bound (the other tile checks its side of the line).
  bool withinBound(VertexId v) {
    borderScratch_.walk(mesh_, v);
    return retriangulateStar(borderScratch_.star, borderScratch_.fill) && cellError(borderScratch_) < INFINITY;
  }

  // A refused border vertex stays here as if it had been kept from the start (its file
  // then reads as the next round's will); the driver keeps it in the other tile too.
  void keepRefused(const std::vector<VertexId>& refused) {
    for (const VertexId v : refused) {
      const TinVertex& p = h_.base.vertices[v];
      h_.borderRefused.push_back(globalCellKey(dem_.globalRow(p.row), dem_.globalCol(p.col)));
      h_.fixed[v] = 1;
    }
  }

  // The candidates of each half of the live list (which is in id order), listed and
  // sorted on a core of its own.
  void sortCandidates() {
    const std::size_t mid = live_.size() / 2;
    auto half = [&](int h, std::size_t begin, std::size_t end) {
      std::vector<Candidate>& candidates = candidates_[h];
      candidates.clear();
      for (std::size_t i = begin; i < end; ++i) {
        const VertexId v = live_[i];
        if (eligible(v) && wanted(importance_[v])) candidates.emplace_back(importance_[v], v);
      }
      std::vector<Candidate> scratch;
      radixSort(candidates, [](const Candidate& c) { return orderedBits(c.first); }, scratch);
      fitted(candidates, candidates.size());
    };
    runBoth([&] { half(0, 0, mid); }, [&] { half(1, mid, live_.size()); });
  }

  // The border rule's picks for the level, first: they block their neighbours, so the
  // level's other picks stay independent of them. A pick this tile cannot delete as one
  // fan would leave a crack beside the other tile, which deletes it: never silently.
  void pickBorders(std::int32_t level, std::vector<Pick>& picks) {
    const double share = 1 - std::pow(1 - options_.deletePct / 100.0, 4);  // a line is thinned every fourth level
    const bool bounded = options_.measure == Measure::Error && std::isfinite(options_.maxError);
    // The bound holds at cells only one tile sees: unless the tiles agree on the line's
    // deletions (TileBorders::agreed), the border stays.
    if (bounded && !tile_->agreed) return;
    std::vector<VertexId> refused;
    // Under a bound, this tile refuses what it cannot delete within it (the other tile then
    // keeps it too): a vertex it cannot delete as one fan is refused, not an error.
    const auto accept = [&](VertexId v) {
      return !bounded || (mesh_.open(v) && mesh_.deletableOpen(v) && withinBound(v));
    };
    const auto taken = borders_.take(level, share, borderLimit(bounded), accept, refused);
    keepRefused(refused);
    for (const auto& [importance, v] : taken) {
      if (v == BorderLines::kNoVertex) continue;  // left out of this tile's level 0
      if (!mesh_.open(v) || !mesh_.deletableOpen(v) || stamp_[v] == level)
        throw Error("tile border vertex at cell (row " + std::to_string(dem_.globalRow(h_.base.vertices[v].row)) +
                    ", column " + std::to_string(dem_.globalCol(h_.base.vertices[v].col)) +
                    ") cannot be deleted in this tile at level " + std::to_string(level) +
                    ", as its neighbour tile deletes it; please report this with the DEM and options");
      stamp_[v] = level;
      mesh_.eachAround(v, [&](std::int32_t slot, int k) {
        stamp_[mesh_.corner(slot, (k + 1) % 3)] = stamp_[mesh_.corner(slot, (k + 2) % 3)] = level;
      });
      picks.push_back({importance, v, static_cast<std::uint32_t>(mesh_.degree(v)), true});
    }
  }

  // The two halves' candidates merged as they are read, ties going to the first half's
  // (smaller ids): the order of one stable sort of them all. Each pick blocks its
  // neighbours (from the ring lines: the picks jump about the TIN).
  void pickBestFirst(std::size_t limit, std::int32_t level, std::vector<Pick>& picks) {
    const std::vector<Candidate>&a = candidates_[0], &b = candidates_[1];
    std::size_t i = 0, j = 0, tiesPicked = 0;
    constexpr std::size_t kAhead = 16;  // the candidates lie all over the TIN: ask ahead for their lines
    while (picks.size() < limit && (i < a.size() || j < b.size())) {
      if (i + kAhead < a.size()) __builtin_prefetch(&stamp_[a[i + kAhead].second]), rings_.prefetch(a[i + kAhead].second);
      if (j + kAhead < b.size()) __builtin_prefetch(&stamp_[b[j + kAhead].second]), rings_.prefetch(b[j + kAhead].second);
      const bool first = firstIsNext(i, j);
      const bool tie = (first ? a[i] : b[j]).first >= tieQuota_.bottom;
      if (tie && tiesPicked == tieQuota_.picks) break;
      const auto [imp, v] = first ? a[i++] : b[j++];
      if (!claim(v, level)) continue;
      picks.push_back({imp, v, static_cast<std::uint32_t>(rings_.degree(v)), mesh_.open(v)});
      tiesPicked += tie;
    }
    stoppedAt_ = {i, j};
  }

  // Whether the merged candidates' next is the first half's (ties go to it: smaller ids).
  bool firstIsNext(std::size_t i, std::size_t j) const {
    const std::vector<Candidate>&a = candidates_[0], &b = candidates_[1];
    return j == b.size() || (i < a.size() && orderedBits(a[i].first) <= orderedBits(b[j].first));
  }

  // Takes v for the level unless a neighbour's pick blocked it; then blocks its neighbours.
  bool claim(VertexId v, std::int32_t level) {
    if (stamp_[v] == level) return false;
    stamp_[v] = level;
    if (rings_.kept(v)) {
      const VertexId* ring = rings_.ring(v);
      for (int k = 0; k < rings_.degree(v); ++k) stamp_[ring[k]] = level;
    } else {
      mesh_.eachAround(v, [&](std::int32_t slot, int k) {
        stamp_[mesh_.corner(slot, (k + 1) % 3)] = stamp_[mesh_.corner(slot, (k + 2) % 3)] = level;
      });
    }
    return true;
  }

  // A survey's level without a threshold goes on past its picks through every candidate,
  // picking (not deleting) as a threshold above them all would: how many of each bin the
  // build pass's threshold for the raster can take in this state, wherever it falls. Past
  // the delete percentage a pick's share is no guide: the later candidates' neighbours are
  // blocked more often.
  std::vector<std::uint64_t> walkOn(std::int32_t level, std::vector<std::uint64_t> histogram) {
    const std::vector<Candidate>&a = candidates_[0], &b = candidates_[1];
    auto [i, j] = stoppedAt_;
    while (i < a.size() || j < b.size()) {
      const auto [imp, v] = firstIsNext(i, j) ? a[i++] : b[j++];
      if (claim(v, level)) ++histogram[surveyBin(imp)];
    }
    return histogram;
  }

  // Where the hierarchy's arrays would end if `picks` vertices were deleted with the
  // last level's mean degree (a twentieth more, so that it rarely falls short).
  Ranges expectedGrowth(std::size_t picks) const {
    const double d = 1.05 * meanDegree_;
    const auto n = [&](double perPick) { return static_cast<std::size_t>(std::ceil(perPick * double(picks))); };
    return {used_.group + picks, used_.triangles + n(d - 2), used_.rings + n(d)};
  }

  // Grows the hierarchy's arrays to at least `to`; unless beyondReserve, only within what
  // was reserved (so they never move while others read them).
  void growHierarchy(const Ranges& to, bool beyondReserve) {
    if (!records_) return;
    auto grow = [&](auto& v, std::size_t n) {
      if (v.size() >= n) return;
      // Past the reserve the array moves: by an eighth more, not the doubling resize makes,
      // since both copies are held while it moves.
      if (beyondReserve && n > v.capacity()) v.reserve(n + n / 8);
      v.resize(beyondReserve ? n : std::min(n, std::max(v.capacity(), v.size())));
    };
    grow(h_.groups, to.group), grow(h_.triangles, to.triangles), grow(h_.rings, to.rings);
  }

  void deleteAll(const std::vector<Pick>& picks, std::int32_t level) {
    const std::size_t ringCount = slots_.size();
    Ranges at = used_;
    used_ = {at.group + picks.size(), at.triangles + fill_.size(), at.rings + ringCount};
    growHierarchy(used_, true);  // where the last level's picks fell short
    if (!records_) at.rings = 0, fitted(h_.rings, ringCount);  // the level's rings only, read below
    if (!picks.empty()) meanDegree_ = double(ringCount) / double(picks.size());
    lastPicks_ = picks.size();
    mesh_.beginRound();
    forEachBlock(static_cast<int>(picks.size()), [&](int begin, int end) {
      Star star;
      std::vector<LocalTriangle> fill;
      for (int i = begin; i < end; ++i) {
        mesh_.prefetchAhead(i, end, [&](int j) { return picks[j].id; });
        plan(picks[i], level, Ranges{at.group + i, at.triangles, at.rings}, star, fill);
      }
    }, [&](double f) { reportProgress(level, f / 2, picks.size()); });
    forEachBlock(static_cast<int>(picks.size()), [&](int begin, int end) {
      for (int i = begin; i < end; ++i) replace(picks[i], at.triangles, at.rings);
    }, [&](double f) { reportProgress(level, 0.5 + f / 2, picks.size()); });
    for (std::size_t k = at.rings; k < at.rings + ringCount; ++k) stale_[h_.rings[k]] = 1;  // the ring vertices' stars changed
    live_.erase(std::remove_if(live_.begin(), live_.end(), [&](VertexId v) { return h_.vertexLevel[v] != kOpenLevel; }),
                live_.end());
    for (const Pick& p : picks) {
      triangles_ -= p.open ? 1 : 2;
      outlineLeft_ -= p.open;
    }
    // The plan is carried out: its arrays go before the compaction, the level's peak.
    releaseMemory(fill_), releaseMemory(slots_), releaseMemory(outer_);
    if (!records_) releaseMemory(h_.rings);
    releaseFreedMemory();  // what the level's selection left
    compact();
    releaseFreedMemory();
  }

  StarView view(const Pick& pick, std::size_t rings) const {
    return {h_.rings.data() + rings + pick.ring, slots_.data() + pick.ring, outer_.data() + pick.ring,
            static_cast<int>(pick.degree), pick.open};
  }

  // The first pass, for one pick: its star, its retriangulation, how far each new
  // triangle is from the DEM, and its group. Reads the mesh and writes only entries that
  // are the pick's own: its ranges of the level's arrays and of the hierarchy's, its
  // star's triangles, its slots' retirement and figures (the new triangles take the
  // first slots in the second pass; no one reads a slot's figures meanwhile).
  void plan(const Pick& pick, std::int32_t level, const Ranges& at, Star& star,
            std::vector<LocalTriangle>& fill) {
    VertexId* ring = h_.rings.data() + at.rings + pick.ring;
    const std::int32_t* outer = outer_.data() + pick.ring;
    mesh_.starOf(pick.id, ring, slots_.data() + pick.ring, outer_.data() + pick.ring, star);
    if (!retriangulateStar(star, fill) || fill.size() + 2 != star.ring.size())
      throw Error("internal error: deleting a vertex of degree " + std::to_string(star.ring.size()) + " made " +
                  std::to_string(fill.size()) + " triangles");
    std::copy(fill.begin(), fill.end(), fill_.begin() + pick.fill);
    const std::int32_t* slots = slots_.data() + pick.ring;
    if (records_) {
      for (std::size_t j = 0; j < fill.size(); ++j)
        slotCells_[slots[j]] = measureFill(ring, outer, static_cast<int>(pick.degree), fill[j]);
      for (std::uint32_t k = static_cast<std::uint32_t>(fill.size()); k < pick.triangles(); ++k) slotCells_[slots[k]] = TriangleCells{};
    }
    thread_local std::vector<int> onEdge;  // by ring edge: the new triangle on it
    onEdge.resize(pick.degree);
    ringEdgeTriangles(fill.data(), static_cast<int>(pick.degree), onEdge.data());
    mesh_.retire(view(pick, at.rings), onEdge.data());
    record(pick, level, at, ring);
  }

  // The group of a pick, which replaces its accept triangles (the star's) and makes its
  // reject triangles (the new ones). The triangles say so; linkGroups indexes them by
  // group when a caller needs it, not in arrays that grow level by level.
  void record(const Pick& pick, std::int32_t level, const Ranges& at, const VertexId* ring) {
    h_.vertexLevel[pick.id] = level - 1;
    if (!records_) return;
    const std::int32_t g = static_cast<std::int32_t>(at.group);
    const std::uint32_t d = pick.degree;
    Group& group = h_.groups[at.group];
    group.vertex = pick.id;
    group.level = level;
    group.importance = pick.importance;
    group.ringBegin = static_cast<std::uint32_t>(at.rings + pick.ring);
    group.ringEnd = group.ringBegin + d;
    for (std::uint32_t k = 0; k < pick.triangles(); ++k) {
      const std::int32_t t = mesh_.triangleId(slots_[pick.ring + k]);
      h_.triangles[t].lastLevel = level - 1;
      h_.triangles[t].replacedBy = g;
    }
    const LocalTriangle* fill = fill_.data() + pick.fill;
    for (std::uint32_t j = 0; j + 2 < d; ++j) {
      const std::size_t t = at.triangles + pick.fill + j;
      HierarchyTriangle& ht = h_.triangles[t];
      ht.v = {ring[fill[j][0]], ring[fill[j][1]], ring[fill[j][2]]};
      ht.firstLevel = level;
      ht.lastLevel = kOpenLevel;
      ht.group = g;
      const double error = slotCells_[slots_[pick.ring + j]].maxError;
      ht.error = roundedUpError(error);
      group.error = std::max(group.error, error);  // exact: the error measure's importance
    }
  }

  // The second pass, for one pick: the new triangles go into the mesh (their figures went
  // into their slots in the first pass). Writes the pick's own slots, and the links back
  // to them.
  void replace(const Pick& pick, std::size_t triangles, std::size_t rings) {
    const StarView star = view(pick, rings);
    std::int32_t ids[kSmallStar];
    std::vector<std::int32_t> many;
    std::int32_t* id = ids;
    if (star.degree - 2 > kSmallStar) many.resize(star.degree - 2), id = many.data();
    for (int j = 0; j + 2 < star.degree; ++j) id[j] = static_cast<std::int32_t>(triangles + pick.fill + j);
    mesh_.replaceStar(star, fill_.data() + pick.fill, id);
  }

  // The level's figures; after compaction every slot holds a triangle of the level.
  LevelStats levelStats(std::int32_t level, std::size_t deleted, double select, double remove) const {
    LevelStats l;
    l.level = level, l.vertices = current_, l.triangles = triangles_, l.deleted = deleted;
    l.selectSeconds = select, l.deleteSeconds = remove;
    double sum = 0;
    for (const TriangleCells& c : slotCells_) l.maxError = std::max(l.maxError, c.maxError), sum += c.sumSquares, l.cells += c.cells;
    l.rmse = l.cells > 0 ? std::sqrt(sum / double(l.cells)) : 0;
    l.outlineVertices = outlineLeft_;
    return l;
  }

  // Why no level could be made: the first reason that applies.
  std::string whyStopped(std::size_t picked) const {
    const std::size_t fixed = static_cast<std::size_t>(std::count(h_.fixed.begin(), h_.fixed.end(), 1));
    std::string why = picked == 0 ? "no vertex left could go" : "the next level would delete only " + std::to_string(picked) +
                                                                  " vertices, under 1 % of them";
    if (options_.measure == Measure::Error && std::isfinite(options_.maxError))
      return why + ": deleting any other would take some DEM cell further than -max_error " +
             formatNumber(options_.maxError) + " m (or level 0's own distance there) from the surface";
    if (options_.thresholdMode) return why + ": the others' importance is not below -threshold";
    if (options_.measure == Measure::Degree) return why + ": the others have a degree above -max_degree " + std::to_string(options_.maxDegree);
    return why + ": " + std::to_string(fixed) + " vertices are fixed (raster corners, outline vertices where two parts of "
           "the TIN touch, points to keep" + (options_.keepOutline ? ", the outline with -keep_outline)"
                                          : ") and " + std::to_string(outlineLeft_) +
                                                " are on the outline, where they go only while it moves less than -outline_tolerance");
  }

  // `within` of the way through deleting `deleting` vertices to make `level`.
  void reportProgress(std::int32_t level, double within, std::size_t deleting) {
    const double span = std::max<double>(1.0, double(original_) - double(stopCount_));
    const double gone = double(original_) - double(current_) + within * double(deleting);
    lastFraction_ = std::clamp(0.1 + 0.9 * gone / span, 0.1, 1.0);
    progress_.report(lastFraction_, "Simplifying level " + std::to_string(level));
  }

  void finish() {
    if (records_) {
      h_.groups.resize(used_.group), h_.triangles.resize(used_.triangles);
      h_.rings.resize(used_.rings);
    }
    const std::int32_t top = h_.coarsest();
    for (HierarchyTriangle& t : h_.triangles)
      if (t.lastLevel == kOpenLevel) t.lastLevel = top;
    for (std::int32_t& l : h_.vertexLevel)
      if (l == kOpenLevel) l = top;
  }

  const HierarchyOptions& options_;
  // A survey is written as figures only: the levels' triangles, groups and rings,
  // which grow with every level to the largest part of the memory, are not kept.
  const bool records_ = !options_.survey;
  ProgressRange progress_;
  const Dem& dem_;
  const TileBorders* tile_;
  BorderLines borders_;
  StarScratch borderScratch_;  // withinBound's, on the selecting thread
  Hierarchy h_;
  SimplificationMesh mesh_;
  CellErrors cells_;
  OutlineChain outline_;
  std::size_t outlineLeft_ = 0;      // outline vertices in the current level
  double cellSize_ = 0, tolerance_ = 0;  // metres; the outline's tolerance at level 1
  std::vector<VertexId> live_;               // vertices not fixed and not yet deleted
  std::vector<double> importance_;           // by vertex
  std::vector<std::int32_t> stamp_;          // by vertex: the level in which it or a neighbour was picked
  std::vector<std::uint8_t> stale_;          // by vertex: its importance must be recomputed
  VertexRings rings_;                        // by vertex: its neighbours, as last measured
  std::vector<TriangleCells> slotCells_;     // by slot: its triangle against the DEM
  using Candidate = std::pair<double, VertexId>;
  std::vector<Candidate> candidates_[2];     // the level's, by importance, in two halves
  std::vector<LocalTriangle> fill_;          // the level's plan: each pick's new triangles
  std::vector<std::int32_t> slots_;          //   and each pick's star slots
  std::vector<std::int32_t> outer_;          //   and the triangles beyond its ring
  std::size_t original_ = 0, stopCount_ = 0, current_ = 0, triangles_ = 0;
  Ranges used_{};            // how much of the hierarchy's arrays is written; beyond, grown ahead
  double meanDegree_ = 6.0;  // of the last level's picks (a Delaunay TIN's mean degree is 6)
  std::size_t lastPicks_ = 0;
  double lastFraction_ = 0.1;
  double levelThreshold_ = 0;  // with levelThresholds: the level's
  TieQuota tieQuota_;          //   and how many of its bin's candidates may go
  std::pair<std::size_t, std::size_t> stoppedAt_;  // where the last pick stopped in each half's candidates
};

}  // namespace

Hierarchy buildHierarchy(Tin base, const Dem& dem, std::vector<std::uint8_t> fixed, const HierarchyOptions& options,
                         const ProgressRange& progress, const std::vector<PointXY>& keep, const TileBorders* tile) {
  options.validate();
  Hierarchy h = Simplifier(std::move(base), dem, std::move(fixed), options, progress, tile).run(keep);
  // Level 0's triangles, which the simplifier dropped from the TIN (their ids are their
  // places in it), once its own arrays are freed.
  const std::size_t levelZero = h.triangles.empty() ? 0 : h.levels.front().triangles;
  h.base.triangles.reserve(levelZero);
  for (std::size_t t = 0; t < levelZero; ++t) h.base.triangles.push_back(h.triangles[t].v);
  return h;
}

}  // namespace tinlod
