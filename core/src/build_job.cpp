// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/build_job.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <unordered_set>

#include "dataset_files.h"
#include "grid_bend.h"
#include "interior_share.h"
#include "release_memory.h"
#include "text_and_paths.h"
#include "tinlod/crs_transform.h"
#include "tinlod/dem_reader.h"
#include "tinlod/hierarchy_builder.h"
#include "tinlod/hierarchy_writer.h"
#include "tinlod/output_files.h"
#include "tinlod/point_reader.h"
#include "tinlod/sample_job.h"
#include "tinlod/tile_reader.h"
#include "tinlod/error.h"
#include "tinlod/version.h"

namespace tinlod {
namespace {

std::map<std::string, std::string> buildMetadata(const std::string& demPath, const SampleOptions& s,
                                                 const HierarchyOptions& o, const std::string& crsName) {
  return {{"TINLOD_VERSION", kVersion},
          {"TINLOD_KIND", "hierarchy"},
          {"TINLOD_SOURCE", recordedPath(demPath)},
          {"TINLOD_CRS", crsName},
          {"TINLOD_BAND", std::to_string(s.band)},
          {"TINLOD_VALID_RANGE", s.validHeights.text()},
          {"TINLOD_BLOCK", std::to_string(s.block)},
          {"TINLOD_JITTER", formatNumber(s.jitter)},
          {"TINLOD_SEED", std::to_string(s.seed)},
          {"TINLOD_SOURCE_SRS", s.sourceSrs.empty() ? "from file" : s.sourceSrs},
          {"TINLOD_TARGET_SRS", s.targetSrs.empty() ? "auto" : s.targetSrs},
          {"TINLOD_METHOD", measureName(o.measure)},
          {"TINLOD_DELETE_PCT", o.thresholdMode ? "none (threshold mode)" : formatNumber(o.deletePct)},
          {"TINLOD_STOP_PCT", formatNumber(o.stopPct)},
          {"TINLOD_MAX_LEVELS", o.maxLevels == 0 ? "no limit" : std::to_string(o.maxLevels)},
          {"TINLOD_MAX_DEGREE", o.measure == Measure::Degree ? std::to_string(o.maxDegree) : "none (degree method only)"},
          {"TINLOD_MAX_ERROR", o.maxError == INFINITY ? "none" : formatNumber(o.maxError)},
          {"TINLOD_THRESHOLD", o.thresholdMode ? formatNumber(o.threshold) : "none"},
          {"TINLOD_FIX_PEAKS_PITS", o.fixPeaksPits ? "yes" : "no"},
          {"TINLOD_OUTLINE", o.keepOutline ? "kept" : std::isnan(o.outlineTolerance) ? "tolerance one cell"
                                                                                     : "tolerance " + formatNumber(o.outlineTolerance) + " m"},
          {"TINLOD_FIXED_POINTS", o.fixedPoints.empty() ? "none" : o.fixedPoints}};
}

// The stop percentage may be out of reach (fixed vertices, an error bound, an outline that
// may not move further): say why rather than leave the user guessing.
void warnIfStoppedEarly(const Hierarchy& h, const ProgressRange& progress) {
  if (h.stopReason.empty()) return;
  const std::size_t target = static_cast<std::size_t>(std::ceil(h.options.stopPct / 100.0 * h.levels.front().vertices));
  progress.warn("stopped at " + std::to_string(h.levels.back().vertices) + " vertices, above the " +
                formatNumber(h.options.stopPct) + " % asked for (" + std::to_string(target) + "): " + h.stopReason);
}

// Only where the target was out of reach: a build that reached it stopped where it was told
// (the -stop_pct this warning names, taken, warns no more). An error bound keeps the inside's
// surface whatever it keeps of its vertices.
void warnIfInteriorStarved(const Hierarchy& h, const ProgressRange& progress) {
  if (h.stopReason.empty() || (h.options.measure == Measure::Error && std::isfinite(h.options.maxError))) return;
  const std::string warning = starvedInteriorWarning(h.levels, h.options.stopPct);
  if (!warning.empty()) progress.warn(warning);
}

// The error method bounds each cell by max(-max_error, level 0's distance there): where the
// sample alone is further than -max_error, the bound is the sample's, which an analyst
// asking for 20 m should hear (mandakini_90m: 329 m).
void noteSampleAboveMaxError(const Hierarchy& h, const SampleOptions& sample, const ProgressRange& progress) {
  const HierarchyOptions& o = h.options;
  if (o.measure != Measure::Error || !std::isfinite(o.maxError) || !(h.levels.front().maxError > o.maxError)) return;
  progress.inform("level 0, the sample of one cell per " + std::to_string(sample.block) + " x " +
                  std::to_string(sample.block) + " block, is already up to " + formatNumber(h.levels.front().maxError) +
                  " m from the DEM, more than -max_error " + formatNumber(o.maxError) +
                  " m: there the bound is level 0's own distance" +
                  (sample.block > 1 ? "; -block 1 samples every cell" : ""));
}

int tileLevels(const HierarchyOptions& o) {
  return o.maxLevels > 0 ? o.maxLevels : tileLevelCount(o.deletePct, o.stopPct);
}

// Every tile of a job must cut the raster alike and make the same levels.
void validateTile(const TileSpec& tile, const SampleOptions& sample, const HierarchyOptions& options) {
  if (tile.size < 2 * sample.block || tile.size % sample.block != 0)
    throw Error("-tile_size " + std::to_string(tile.size) + " must be a multiple of -block (" + std::to_string(sample.block) +
                ") and at least two blocks: tiles are cut along block lines, e.g. -tile_size " +
                std::to_string(std::max(2, 4096 / sample.block) * sample.block));
  if (!options.levelThresholds.empty() && static_cast<int>(options.levelThresholds.size()) < tileLevels(options))
    throw Error("-level_thresholds gives " + std::to_string(options.levelThresholds.size()) + " thresholds for " +
                std::to_string(tileLevels(options)) + " levels: give one per level");
  if (tileLevels(options) > kMaxLevel)
    throw Error("-delete_pct " + formatNumber(options.deletePct) + " and -stop_pct " + formatNumber(options.stopPct) +
                " make " + std::to_string(tileLevels(options)) + " levels in every tile, more than the " +
                std::to_string(kMaxLevel) + " a hierarchy holds: raise -delete_pct or -stop_pct, or give -max_levels");
  if (options.thresholdMode && options.maxLevels == 0)
    throw Error("-threshold in a tiled run needs -max_levels: every tile of a job must make the same levels");
  if (options.survey && !options.lineOutline.empty() && options.levelThresholds.empty())
    throw Error("-line_outline is for the build pass, or a second -survey with its -level_thresholds: a first "
                "-survey lists the tile's own outline cells");
}

// -level_thresholds as given (t[:s],...), to a few digits: the catalogue holds them exactly.
std::string levelThresholdsText(const HierarchyOptions& options) {
  std::string text;
  for (std::size_t k = 0; k < options.levelThresholds.size(); ++k) {
    text += (k ? "," : "") + formatNumber(options.levelThresholds[k]);
    if (k < options.levelShares.size() && options.levelShares[k] < 1) text += ":" + formatNumber(options.levelShares[k]);
  }
  return text;
}

// What a tile was built with beside the options every build records: a tile opened alone
// says how many levels its job makes, and the raster's thresholds it deleted by.
void addTileMetadata(const Dem& dem, const TileSpec& tile, const HierarchyOptions& options,
                     std::map<std::string, std::string>& m) {
  const auto pair = [](std::int64_t a, std::int64_t b) { return std::to_string(a) + "," + std::to_string(b); };
  m["TINLOD_TILE"] = pair(tile.col, tile.row);
  m["TINLOD_TILE_LEVELS"] = std::to_string(tileLevels(options) + 1) + " (levels 0 to " + std::to_string(tileLevels(options)) +
                            ", as every tile of its job)";
  if (!options.levelThresholds.empty())
    m["TINLOD_LEVEL_THRESHOLDS"] = levelThresholdsText(options) + " (the raster's, one per level, from its tiles' surveys)";
  m["TINLOD_TILE_SIZE"] = std::to_string(tile.size);
  m["TINLOD_TILE_WINDOW"] = pair(dem.window.colOffset, dem.window.rowOffset) + "," + pair(dem.width, dem.height);
  m["TINLOD_RASTER_SIZE"] = pair(dem.wholeWidth(), dem.wholeHeight());
}

// A tile whose valid cells make no triangle is empty, not an error. Peaks and pits to fix
// are sampled, every one: fixing only those the blocks' random cells hit kept 88 of
// mandakini_90m's 665.
Tin sampleTile(const Dem& dem, SampleOptions sample, const HierarchyOptions& options, const TileSpec& tile,
               const ProgressRange& progress) {
  sample.peaksAndPits = options.fixPeaksPits;
  if (tile.size == 0) return sampleTin(dem, sample, progress);
  try {
    return sampleTin(dem, sample, progress);
  } catch (const NoTriangle&) {
    throw EmptyTile("tile " + std::to_string(tile.col) + "," + std::to_string(tile.row) + " holds no triangle");
  }
}

// One cell of the whole raster, at its centre, in the TIN's CRS: the same in every tile.
double cellAreaInTin(const Dem& dem, const SampleOptions& sample) {
  const CrsTransform toTin = CrsTransform::forDem(dem, sample.sourceSrs, sample.targetSrs, ProgressRange(Feedback{}, 0, 1));
  const std::array<double, 6>& g = dem.wholeGeotransform();
  const double col = 0.5 * dem.wholeWidth(), row = 0.5 * dem.wholeHeight();
  std::vector<double> x, y;
  for (const auto& [dc, dr] : {std::pair{0.0, 0.0}, std::pair{1.0, 0.0}, std::pair{0.0, 1.0}}) {
    x.push_back(g[0] + (col + dc) * g[1] + (row + dr) * g[2]);
    y.push_back(g[3] + (col + dc) * g[4] + (row + dr) * g[5]);
  }
  toTin.apply(x, y);
  const double area = std::fabs((x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]));
  return std::isfinite(area) && area > 0 ? area : std::fabs(g[1] * g[5]);
}

// A file of cells for `option` (-border_keep, -line_outline): one "row col" of the whole
// raster per line ('#' starts a comment).
std::unordered_set<std::uint64_t> readCellList(const std::string& path, const std::string& option) {
  std::ifstream in(path);
  if (!in) throw Error(option + ": cannot read '" + path + "': give the file of line cells (tinlod tiles writes it)");
  std::unordered_set<std::uint64_t> cells;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    line = line.substr(0, line.find('#'));
    std::istringstream fields(line);
    std::int64_t row = -1, col = -1;
    std::string rest;
    if (!(fields >> row)) continue;  // a blank line
    if (!(fields >> col) || (fields >> rest) || row < 0 || col < 0 || row > INT32_MAX || col > INT32_MAX)
      throw Error(option + ": line " + std::to_string(number) + " of '" + path +
                  "' is not a cell \"row col\" of the raster (two whole numbers from 0)");
    cells.insert(globalCellKey(row, col));
  }
  return cells;
}

// `kept`: -border_keep's cells, or none for a tile whose lines need no agreement;
// `outline`: -line_outline's cells, or none (every line cell near nodata pinned).
TileBorders bordersOf(const Dem& dem, const Tin& tin, const TileSpec& tile, const SampleOptions& sample,
                      const HierarchyOptions& options, std::optional<std::unordered_set<std::uint64_t>> kept,
                      std::optional<std::unordered_set<std::uint64_t>> outline) {
  TileBorders b = kept ? agreedTileBorders(dem, tin, tile, tileLevels(options), sample.block, sample.seed,
                                           cellAreaInTin(dem, sample), options.fixPeaksPits, std::move(*kept))
                       : tileBorders(dem, tin, tile, tileLevels(options), sample.block, sample.seed,
                                     cellAreaInTin(dem, sample), options.fixPeaksPits);
  if (outline) pinLineOutlineOnly(b, dem, tin, std::move(*outline), "-line_outline: '" + options.lineOutline + "'");
  return b;
}

std::optional<std::unordered_set<std::uint64_t>> keptCellsOf(const HierarchyOptions& options) {
  if (options.borderKeep.empty()) return std::nullopt;
  return readCellList(options.borderKeep, "-border_keep");
}

std::optional<std::unordered_set<std::uint64_t>> outlineCellsOf(const HierarchyOptions& options) {
  if (options.lineOutline.empty()) return std::nullopt;
  return readCellList(options.lineOutline, "-line_outline");
}

std::string cellList(const std::vector<std::uint64_t>& keys) {
  std::string text;
  for (const std::uint64_t key : keys)
    text += (text.empty() ? "" : ";") + std::to_string(globalCellRow(key)) + " " + std::to_string(globalCellCol(key));
  return text;
}

// What the driver of an agreed job reads back: the line cells this tile was told to keep,
// and those it refused (which the tile beyond the line must keep too).
void addAgreementMetadata(const Dem& dem, const TileBorders& borders, const Hierarchy& h,
                          std::map<std::string, std::string>& m, const ProgressRange& progress) {
  if (!borders.agreed) return;
  m["TINLOD_BORDER_AGREED"] = "yes";  // GDAL drops empty items: the two lists below may be absent
  m["TINLOD_BORDER_KEPT"] = cellList(cellsOnSharedLines(dem, borders.kept));
  std::vector<std::uint64_t> refused = h.borderRefused;
  std::sort(refused.begin(), refused.end());
  m["TINLOD_BORDER_REFUSED"] = cellList(refused);
  if (refused.size() == 1)
    progress.warn("1 border vertex would take cells of this tile beyond -max_error; it stayed here, so the tile "
                  "beside it must keep it too (tinlod tiles does so, adding it to the -border_keep file and building "
                  "both again): TINLOD_BORDER_REFUSED lists it");
  else if (!refused.empty())
    progress.warn(std::to_string(refused.size()) + " border vertices would take cells of this tile beyond -max_error; "
                  "they stayed here, so the tiles beside them must keep them too (tinlod tiles does so, "
                  "adding them to the -border_keep file and building both again): TINLOD_BORDER_REFUSED lists them");
}

const std::string kFixedName = "-fixed (points to keep)";

// A tile makes exactly tileLevels levels: a view beyond them would be missing from every
// tile, where a whole run only warns (its levels are known at the end).
void validateTileViews(const HierarchyLayers& layers, const HierarchyOptions& options) {
  const int levels = tileLevels(options);
  for (const std::int32_t level : layers.levelViews)
    if (level != HierarchyLayers::kCoarsest && level > levels)
      throw Error("-levels " + levelListText(layers.levelViews) + ": every tile makes levels 0 to " +
                  std::to_string(levels) + " (-max_levels, or -delete_pct and -stop_pct): give levels up to " +
                  std::to_string(levels) + ", or last");
}

// The checks of the options alone, before anything is read.
void validateBuildOptions(const SampleOptions& sample, const HierarchyOptions& options, const AccuracyOutputs& accuracy,
                          const HierarchyLayers& layers, const TileSpec& tile) {
  sample.validateForHierarchy();
  options.validate();
  if (tile.size > 0) validateTile(tile, sample, options), validateTileViews(layers, options);
  accuracy.validate();
  if (!options.levelThresholds.empty() && tile.size == 0)
    throw Error("-level_thresholds is the second pass of a tiled run: give it with -tile_size and -tile");
  if (!options.borderKeep.empty() && tile.size == 0)
    throw Error("-border_keep is for a tile of a job with -method error -max_error: give it with -tile_size and -tile");
  if (!options.lineOutline.empty() && tile.size == 0)
    throw Error("-line_outline is for a tile of a job: give it with -tile_size and -tile");
}

// Measured on alps_2x2 with -block 1, 3 and 5 (306 MiB at 3): the DEM and its cells'
// records, and each sampled vertex through the levels.
MemoryUse buildMemory(const SampleOptions& sample) {
  const std::string tiles = "cut it into tiles with tinlod tiles (memory bounded by the tile)";
  return {"building its hierarchy", 13 + 400.0 / (double(sample.block) * sample.block),
          tiles + ", or sample fewer cells with a larger -block", 13, tiles};
}

Dem readInput(const std::string& demPath, const SampleOptions& sample, const TileSpec& tile, const ProgressRange& progress) {
  if (tile.size > 0) return readTile(demPath, sample.band, tile, pinningDistance(sample.block), progress, sample.validHeights);
  const MemoryUse use = buildMemory(sample);
  return readDem(demPath, sample.band, progress, sample.validHeights, &use);
}

// The levels are measured on the DEM's grid: no triangle of theirs may turn over in the TIN's
// CRS, and the coarsest, whose triangles are the largest, should read the same there.
void checkBuildGridBend(const Dem& dem, const CrsTransform& toTin, const Hierarchy& h, const ProgressRange& progress) {
  const std::vector<std::uint32_t> coarsest = h.levelTriangles(h.coarsest());
  checkGridBend(
      dem, toTin, h.base.vertices, h.triangles.size(), [&h](std::size_t i) -> const Triangle& { return h.triangles[i].v; },
      coarsest.size(), [&](std::size_t i) -> const Triangle& { return h.triangles[coarsest[i]].v; },
      h.levels.back().maxError, "level " + std::to_string(h.coarsest()), progress);
}

// A survey pass of a tiled run with one threshold per level: the levels are made as usual
// (each tile deleting its share, or as earlier thresholds say) to see what each level's
// candidates are worth, and only that is written (LevelSurvey, as JSON): no hierarchy.
BuildSummary runSurvey(const std::string& demPath, const std::string& outPath, const SampleOptions& sample,
                       const HierarchyOptions& options, bool overwrite, const Feedback& feedback, const TileSpec& tile) {
  if (!overwrite && std::filesystem::exists(outPath))
    throw Error("'" + outPath + "' exists: add -overwrite to replace it");
  const ProgressRange all(feedback, 0, 1);
  const Dem dem = readInput(demPath, sample, tile, all.sub(0, 0.05));
  Tin tin = sampleTile(dem, sample, options, tile, all.sub(0.05, 0.2));
  // The tile pins its own outline's line cells: the other tile's are not known yet (the
  // survey lists this tile's for the build pass, which pins both tiles' alike). A second
  // survey (tinlod tiles -exact_stop) pins the job's list, as the build pass does.
  std::vector<std::uint64_t> outline;
  if (tile.size > 0) outline = lineOutlineCells(dem, tin, sample.block, sample.seed);
  std::optional<std::unordered_set<std::uint64_t>> pinned = outlineCellsOf(options);
  if (!pinned) pinned.emplace(outline.begin(), outline.end());
  const TileBorders borders =
      tile.size > 0 ? bordersOf(dem, tin, tile, sample, options, keptCellsOf(options), std::move(pinned)) : TileBorders{};
  std::vector<std::uint8_t> fixed = options.fixPeaksPits ? peaksAndPits(dem, tin) : std::vector<std::uint8_t>();
  const Hierarchy h = buildHierarchy(std::move(tin), dem, std::move(fixed), options, all.sub(0.2, 0.95), {},
                                     tile.size > 0 ? &borders : nullptr);
  checkBuildGridBend(dem, CrsTransform::forDem(dem, sample.sourceSrs, sample.targetSrs, ProgressRange(Feedback{}, 0, 1)), h, all);
  const std::string partial = outPath + ".partial";
  {
    errno = 0;
    std::ofstream out(partial);
    out << surveyJson(h.survey, outline);
    out.close();
    if (!out) throw Error("cannot write '" + partial + "': " + whyWriteFailed(std::filesystem::path(partial).parent_path()));
  }
  std::filesystem::rename(partial, outPath);
  all.finish("Done");
  BuildSummary s;
  s.levels = h.coarsest();
  s.originalVertices = h.levels.front().vertices;
  s.coarsestVertices = h.levels.back().vertices;
  return s;
}

}  // namespace

std::vector<std::uint8_t> peaksAndPits(const Dem& dem, const Tin& tin) {
  std::vector<std::uint8_t> fixed(tin.vertices.size(), 0);
  for (std::size_t i = 0; i < tin.vertices.size(); ++i) {
    const TinVertex& v = tin.vertices[i];
    fixed[i] = strictPeakOrPit(dem, v.row, v.col);
  }
  return fixed;
}

void checkBuildJob(const std::string& demPath, const SampleOptions& sample, const HierarchyOptions& options,
                   const AccuracyOutputs& accuracy, const HierarchyLayers& layers, const TileSpec& tile,
                   const Feedback& feedback) {
  validateBuildOptions(sample, options, accuracy, layers, tile);
  keptCellsOf(options);
  outlineCellsOf(options);
  if (!options.fixedPoints.empty()) checkPointsExist(options.fixedPoints, kFixedName);
  // Two cells at the middle of the tile, or of the raster: enough for the CRS and the jitter.
  const std::array<int, 2> raster = rasterSize(demPath);
  const CellWindow whole{0, 0, raster[0], raster[1]};
  const CellWindow area = tile.size > 0 ? tileWindow(raster, tile) : whole;
  CellWindow middle;
  middle.xsize = std::min(2, raster[0]), middle.ysize = std::min(2, raster[1]);
  middle.xoff = std::min(area.xoff + area.xsize / 2, raster[0] - middle.xsize);
  middle.yoff = std::min(area.yoff + area.ysize / 2, raster[1] - middle.ysize);
  const Dem two = readDemWindow(demPath, sample.band, middle, ProgressRange(Feedback{}, 0, 1), sample.validHeights);
  samplingTransform(two, sample, ProgressRange(feedback, 0, 1));  // its warnings and notes are the build's
  if (tile.size == 0) checkMemory(demPath, raster[0], raster[1], buildMemory(sample), ProgressRange(feedback, 0, 1));
}

BuildSummary runBuildJob(const std::string& demPath, const std::string& outPath, const SampleOptions& sample,
                         const HierarchyOptions& options, bool overwrite, const Feedback& feedback,
                         const AccuracyOutputs& accuracy, const HierarchyLayers& layers, const TileSpec& tile) {
  validateBuildOptions(sample, options, accuracy, layers, tile);
  if (options.survey) return runSurvey(demPath, outPath, sample, options, overwrite, feedback, tile);
  // Bad files fail before the long work.
  std::optional<std::unordered_set<std::uint64_t>> kept = keptCellsOf(options), outline = outlineCellsOf(options);
  GpkgWriteOptions writeOptions{overwrite, {{"TINLOD_KIND", "hierarchy"}}};  // the kind: refuse another's file now
  // The hierarchy and the accuracy files go into place together, or none of them.
  OutputFiles files(overwrite, datasetFiles({demPath, options.fixedPoints}));
  files.refuseInput(outPath, "output");  // first: an input's folder may be read-only
  const std::string held = checkOutputPath(outPath, writeOptions);  // fail before the long work, not after it
  if (!options.fixedPoints.empty()) checkPointsExist(options.fixedPoints, kFixedName);
  const StagedFile& out = files.add(outPath, "output", true);
  const AccuracyFiles accuracyFiles = stageAccuracyFiles(accuracy, files);
  const ProgressRange all(feedback, 0, 1);
  warnOfReplacedKind(outPath, held, writeOptions, all);
  Dem dem = readInput(demPath, sample, tile, all.sub(0, 0.05));
  Tin tin = sampleTile(dem, sample, options, tile, all.sub(0.05, 0.2));
  std::vector<std::uint8_t> fixed = options.fixPeaksPits ? peaksAndPits(dem, tin) : std::vector<std::uint8_t>();
  const TileBorders borders =
      tile.size > 0 ? bordersOf(dem, tin, tile, sample, options, std::move(kept), std::move(outline)) : TileBorders{};
  const std::vector<PointXY> keep =
      options.fixedPoints.empty() ? std::vector<PointXY>() : readPoints(options.fixedPoints, tin.crsWkt, all, kFixedName);
  // With accuracy outputs the last quarter of the job is theirs.
  const double write = accuracy.wanted() ? 0.6 : 0.75, measure = accuracy.wanted() ? 0.75 : 1;
  Hierarchy h = buildHierarchy(std::move(tin), dem, std::move(fixed), options, all.sub(0.2, write), keep,
                               tile.size > 0 ? &borders : nullptr);
  if (tile.size == 0) warnIfStoppedEarly(h, all), warnIfInteriorStarved(h, all), noteSampleAboveMaxError(h, sample, all);
  const CrsTransform toTin = CrsTransform::forDem(dem, sample.sourceSrs, sample.targetSrs, ProgressRange(Feedback{}, 0, 1));
  checkBuildGridBend(dem, toTin, h, all);
  const std::size_t validCells = tile.size > 0 ? 0 : dem.validCount();  // a tile's window holds its halo's too
  // Only the accuracy outputs read the heights and level 0's TIN again; freed, they leave
  // the writing room (68 and 45 MB for a 4096 x 4096 tile). The DEM's size and window stay
  // for the metadata.
  if (!accuracy.wanted()) {
    releaseMemory(dem.z), releaseMemory(dem.nearNodata), releaseMemory(dem.nextToNodata);
    releaseMemory(h.base.triangles);
  }
  writeOptions.metadata = buildMetadata(demPath, sample, options, h.base.crsName);
  if (tile.size > 0) addTileMetadata(dem, tile, options, writeOptions.metadata);
  if (tile.size > 0) addAgreementMetadata(dem, borders, h, writeOptions.metadata, all);
  if (borders.outlineListed)  // how many of the -line_outline cells are on this tile's lines
    writeOptions.metadata["TINLOD_LINE_OUTLINE_CELLS"] =
        std::to_string(cellsOnSharedLines(dem, borders.lineOutline).size());
  writeOptions.metadata["TINLOD_LEVEL_VIEWS"] = levelListText(layers.levelViews);
  writeOptions.metadata["TINLOD_GROUP_OUTLINES"] = layers.groupOutlines ? "yes" : "no";
  writeOptions.metadata["TINLOD_VERTEX_INDEX"] = layers.vertexIndex ? "yes" : "no";
  all.inform("Writing " + std::to_string(h.coarsest() + 1) + " levels: " + std::to_string(h.triangles.size()) +
             " distinct triangles, " + std::to_string(h.groups.size()) + " groups");
  writeHierarchyGpkg(h, out, writeOptions, all.sub(write, measure), layers);
  BuildSummary s;
  if (accuracy.wanted()) {
    s.accuracy = measureAndWrite(dem, h, toTin, accuracy, accuracyFiles, all.sub(measure, 1)).rows;
  }
  files.commit();
  all.finish("Done");

  s.levelViews = layers.views(h.coarsest());
  s.originalVertices = h.levels.front().vertices;
  s.coarsestVertices = h.levels.back().vertices;
  s.coarsestTriangles = h.levels.back().triangles;
  s.fixedVertices = static_cast<std::size_t>(std::count(h.fixed.begin(), h.fixed.end(), 1));
  s.levels = h.coarsest();
  s.coarsestError = h.levels.back().maxError;
  s.coarsestRmse = h.levels.back().rmse;
  s.cellsGivenUp = h.levels.front().cells - h.levels.back().cells;
  s.validCells = validCells;
  s.levelZeroCells = h.levels.front().cells;
  s.fileBytes = std::filesystem::file_size(outPath);
  s.crsName = h.base.crsName;
  return s;
}

}  // namespace tinlod
