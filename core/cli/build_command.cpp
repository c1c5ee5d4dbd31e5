// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>
#include <iostream>

#include "accuracy_arguments.h"
#include "arguments.h"
#include "commands.h"
#include "sample_arguments.h"
#include "terminal_feedback.h"
#include "tinlod/build_job.h"
#include "tinlod/build_summary_text.h"
#include "tinlod/error.h"

namespace tinlod::cli {
namespace {

const char* const kUsage =
    "tinlod build DEM OUT.gpkg [-method degree|volume|normal|error] [-delete_pct p] [-stop_pct s] "
    "[-max_levels n] [-max_degree d] [-max_error m] [-threshold t] [-outline_tolerance m] [-keep_outline] "
    "[-tile_size N -tile C,R [-survey | -level_thresholds t[:s],...] [-border_keep FILE] [-line_outline FILE]] "
    "[-fixed POINTS] [-fix_peaks_pits] [-levels all|L,L,...] [-no_group_outlines] [-vertex_index] "
    "[sampling options] [accuracy options] [-check] [-overwrite] [-q]";

const char* const kHelp = R"(Samples a DEM into a TIN and simplifies it level by level into a triangulation
hierarchy (Kirkpatrick's, as adapted to terrains by de Berg and Dobrindt), written to one
GeoPackage.

Usage: tinlod build DEM OUT.gpkg [options]

Simplification:
  -method m        importance of a vertex, least important deleted first (default volume):
                   degree  its degree; only vertices of degree <= -max_degree go
                   volume  |change of the volume under its neighbourhood| when deleted
                   normal  1 - mean dot product of its triangles' unit normals with their mean
                   error   largest vertical distance, after its deletion, to the DEM at every
                           valid cell centre under its new triangles
  -delete_pct p    at most p % of the current vertices deleted per level (default 20); an
                   independent set rarely holds more than about a quarter of them
  -stop_pct s      stop when s % of the original vertices remain (default 5)
  -max_levels n    stop after n levels above level 0 (default: no limit); a level that
                   would delete under 1 % of its vertices is never made
  -max_degree d    degree method: largest degree deleted (default 11, Kirkpatrick's); refused
                   with the other methods
  -max_error m     error method: a vertex goes only if, at every valid cell centre under
                   its new triangles, the surface stays within max(m, level 0's own
                   distance there) of the DEM; so every level is, at every valid cell
                   centre it covers (level 0 is a sample of the DEM and may already be
                   further than m)
  -threshold t     the study's threshold mode: per level, delete every independent vertex
                   whose importance is below t, instead of -delete_pct; t is in the method's
                   units: cubic metres (volume), metres (error), a degree (degree), or
                   1 - flatness (normal)
  -fixed POINTS    vector file of points whose nearest vertices are never deleted
                   (each point of a multipoint too; lines and polygons are refused)
  -fix_peaks_pits  never delete strict local maxima and minima of the DEM (3 x 3)
  -outline_tolerance m
                   how far the outline of the data and of its holes may move when its
                   vertices go, in metres at level 1 (default: one DEM cell), growing with
                   the levels as the spacing of the vertices does (x sqrt(level 0's vertices
                   / the level's)); the outline never moves out over nodata, and a raster
                   edge stays on its line (a projected DEM keeps its exact rectangle)
  -keep_outline    never delete outline vertices: every level covers level 0's area

One tile of a raster (tinlod tiles runs them all; see docs/cli/tiles.md):
  -tile_size N     cut the raster into tiles of N x N cells (N a multiple of -block), each
                   reading one more column and row, shared with the next tile
  -tile C,R        build tile C,R (from 0,0 at the raster's first column and row). Tiles
                   fit together at every level: both sample the same cells of a shared line
                   (one a block), and a rule that reads only the line thins it alike. Every
                   tile makes -max_levels levels, or the levels -delete_pct and -stop_pct
                   give (14 by default). Exit code 3: the tile holds no data (nothing written)
  -survey          the first pass of one threshold per level: make the levels as usual but
                   write OUT as JSON, each level's candidates by importance (no GeoPackage)
  -level_thresholds t,t,...
                   the second pass: level k deletes every independent vertex whose
                   importance is below the k-th threshold (tinlod tiles sets them from the
                   surveys of every tile), instead of -delete_pct of the tile's vertices; t:s
                   lets only the share s of the candidates in t's survey bin go (ties)
  -border_keep FILE
                   with -method error -max_error: delete line vertices too, each only where
                   it keeps this tile's cells within the bound, and keep the line cells FILE
                   lists ("row col" of the whole raster, one a line). A vertex the bound
                   refuses stays and is listed in TINLOD_BORDER_REFUSED: the tile beyond the
                   line must then keep it too. tinlod tiles agrees these lists between tiles;
                   without -border_keep a bounded tile keeps all its line vertices
  -line_outline FILE
                   the second pass: of the line cells near nodata keep only those FILE lists
                   ("row col" of the whole raster, one a line): the cells on the outline of
                   either tile's level 0, which each tile's -survey lists (line_outline)
                   and tinlod tiles gathers (also a second -survey with -level_thresholds,
                   which then makes the build pass's levels). Without it every line cell
                   within 3 blocks of a missing cell stays at every level

What the GeoPackage holds (vertices, triangles, the groups and the levels table are always
written: lod, locate and accuracy need them):
  -levels list     the level_N views to write: all (default), or levels separated by commas,
                   last for the coarsest: -levels 0,5,last
  -no_group_outlines
                   write the groups layer as a table without its outline polygons
                   (about 30 bytes a stored triangle less); the file is still a whole hierarchy
  -vertex_index    also give the vertices layer a spatial index (7 bytes a stored triangle),
                   for drawing it zoomed in; nothing in tinlod reads the vertices by place
Every level is measured against the DEM at every valid cell centre it covers: its largest
and RMS vertical distance, and the cells its outline gave up (levels table, tinlod info).

Sampling options (as tinlod sample): -b band, -s_srs srs, -t_srs srs, -block k, -jitter m
  (above 0 for a hierarchy, whose levels are measured at every DEM cell), -seed n,
  -valid_range min max (heights outside it are nodata; default -12000 9000)
  -check           check the options, the files they name, the DEM's band, size and CRS
                   (with -tile: that the tile is in its grid) and the jitter against its
                   cells, then stop: two cells of the DEM are read and nothing is written
                   (tinlod tiles checks a job's build options so before any tile runs);
                   prints the options in effect: those not at their defaults, numbers as
                   read, by name
  -overwrite       replace existing outputs: tinlod's layers of the GeoPackage (its other
                   layers are kept), the -accuracy raster, the -report; never an input
  -q               quiet: no progress or information, warnings only

@ACCURACY@
Output layers: vertices (with level and fixed), triangles (each distinct triangle once, with
first_level, last_level, group_id, replaced_by, error), level_0, level_1, ... (views: add any
level to the map), groups (2D outline of each deleted vertex's neighbourhood), levels (counts,
times, maximum and RMS error, cells covered and given up, outline vertices per level). `tinlod info OUT.gpkg` describes the file.
)";

// "t" or "t:s" per level: the threshold, and the share of its bin's candidates that may go.
void parseThresholds(const std::string& text, std::vector<double>& thresholds, std::vector<double>& shares) {
  auto number = [](const std::string& part, double low, double high) {
    std::size_t used = 0;
    double v = NAN;
    try {
      v = std::stod(part, &used);
    } catch (const std::exception&) {
    }
    if (used != part.size() || !(v >= low && v <= high))
      throw Error("-level_thresholds: '" + part + "' is not a threshold t (0 or more) or t:s (s a share from 0 to 1); " +
                  "give one per level, separated by commas");
    return v;
  };
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string part = text.substr(start, comma - start);
    const std::size_t colon = part.find(':');
    thresholds.push_back(number(part.substr(0, colon), 0, INFINITY));
    shares.push_back(colon == std::string::npos ? 1.0 : number(part.substr(colon + 1), 0, 1));
    start = comma + 1;
  }
}

// A -levels list as it is meant: each level once, ascending, "last" at the end.
std::vector<std::int32_t> ascendingLevels(std::vector<std::int32_t> levels) {
  std::sort(levels.begin(), levels.end(), [](std::int32_t x, std::int32_t y) {
    return x == HierarchyLayers::kCoarsest ? false : y == HierarchyLayers::kCoarsest || x < y;
  });
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  return levels;
}

void parseTile(const std::string& text, TileSpec& tile) {
  const std::size_t comma = text.find(',');
  try {
    std::size_t end1 = 0, end2 = 0;
    if (comma == std::string::npos) throw std::invalid_argument(text);
    tile.col = std::stoi(text.substr(0, comma), &end1);
    tile.row = std::stoi(text.substr(comma + 1), &end2);
    if (end1 != comma || end2 != text.size() - comma - 1) throw std::invalid_argument(text);
  } catch (const std::exception&) {
    throw Error("-tile '" + text + "' is not a tile: give its column and row of tiles, e.g. -tile 0,0");
  }
}

}  // namespace

int buildCommand(std::vector<std::string> args) {
  Arguments a(std::move(args));
  if (a.flag("--help") || a.flag("-h")) {
    std::string help = kHelp;
    help.replace(help.find("@ACCURACY@"), 10, kAccuracyHelp);
    std::cout << help;
    return 0;
  }
  HierarchyOptions o;
  o.measure = parseMeasure(a.text("-method", measureName(o.measure)));
  o.deletePct = a.number("-delete_pct", o.deletePct);
  o.stopPct = a.number("-stop_pct", o.stopPct);
  o.maxLevels = a.integer("-max_levels", o.maxLevels);
  if (a.given("-max_degree") && o.measure != Measure::Degree)  // even at its default, which validate() cannot tell
    throw Error("-max_degree applies only to -method degree");
  o.maxDegree = a.integer("-max_degree", o.maxDegree);
  o.maxError = a.number("-max_error", o.maxError);
  const double threshold = a.number("-threshold", NAN);
  o.thresholdMode = !std::isnan(threshold);
  o.threshold = threshold;
  o.fixedPoints = a.text("-fixed", "");
  o.fixPeaksPits = a.flag("-fix_peaks_pits");
  o.outlineTolerance = a.number("-outline_tolerance", o.outlineTolerance);
  o.keepOutline = a.flag("-keep_outline");
  const SampleOptions sample = sampleOptions(a);
  const AccuracyOutputs accuracy = accuracyOutputs(a);
  HierarchyLayers layers;
  layers.levelViews = parseLevelList(a.text("-levels", "all"), "-levels");
  a.restate("-levels", levelListText(ascendingLevels(layers.levelViews)), layers.levelViews.empty());
  layers.groupOutlines = !a.flag("-no_group_outlines");
  layers.vertexIndex = a.flag("-vertex_index");
  o.survey = a.flag("-survey");
  parseThresholds(a.text("-level_thresholds", ""), o.levelThresholds, o.levelShares);
  o.borderKeep = a.text("-border_keep", "");
  o.lineOutline = a.text("-line_outline", "");
  TileSpec tile;
  tile.size = a.integer("-tile_size", 0);
  if (a.given("-tile") != (tile.size > 0)) throw Error("-tile C,R and -tile_size N go together: one tile of a raster cut into N x N-cell tiles");
  if (tile.size > 0) parseTile(a.text("-tile", ""), tile);
  const bool check = a.flag("-check");
  const bool overwrite = a.flag("-overwrite");
  const bool quiet = a.flag("-q");
  const std::vector<std::string> files = a.operands(2, kUsage);
  if (check) {
    checkBuildJob(files[0], sample, o, accuracy, layers, tile, terminalFeedback(quiet));
    if (!quiet) {
      // tinlod tiles records this: a rerun that spells the same job otherwise resumes it.
      const std::string options = a.inEffect({"-tile", "-tile_size", "-check", "-overwrite", "-q"});
      std::cout << "The options are good for " << files[0] << "; nothing was written\n"
                << "Options in effect: " << (options.empty() ? "(the defaults)" : options) << std::endl;
    }
    return 0;
  }

  const BuildSummary s =
      runBuildJob(files[0], files[1], sample, o, overwrite, terminalFeedback(quiet), accuracy, layers, tile);
  if (!quiet && o.survey)  // a survey holds no triangles and measures only level 0: no errors to print
    std::cout << "Surveyed " << s.levels << " levels (" << s.originalVertices << " -> " << s.coarsestVertices
              << " vertices): each level's candidates by importance written to " << files[1] << std::endl;
  else if (!quiet)
    std::cout << "Wrote " << s.levels + 1 << (s.levels ? " levels (0 to " + std::to_string(s.levels) + ", " : " level (")
              << s.originalVertices << " -> " << s.coarsestVertices
              << " vertices, " << s.fixedVertices << " fixed; the coarsest level against the DEM: maximum error "
              << s.coarsestError << " m, RMSE " << s.coarsestRmse << " m, " << coarsestCellsText(s) << ") in " << s.crsName << " to " << files[1] << " (" << s.fileBytes / 1000000
              << " MB)" << std::endl;
  if (const std::string cover = levelZeroCoverText(s); !quiet && !o.survey && !cover.empty()) std::cout << cover << std::endl;
  if (!quiet && !s.accuracy.empty()) printAccuracy(s.accuracy, std::cout);
  return 0;
}

}  // namespace tinlod::cli
