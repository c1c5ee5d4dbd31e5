// SPDX-License-Identifier: GPL-3.0-or-later
#include <iostream>

#include "arguments.h"
#include "commands.h"
#include "terminal_feedback.h"
#include "tinlod/locate_job.h"

namespace tinlod::cli {
namespace {

const char* const kUsage = "tinlod locate HIER.gpkg POINTS OUT.gpkg [-level L] [-overwrite] [-q]";

const char* const kHelp = R"(The TIN's elevation at points: each point is located through the hierarchy
(Kirkpatrick's search: the coarsest level, then the triangles each one replaced, down to
the level asked for) and the height of the containing triangle is interpolated.

Usage: tinlod locate HIER.gpkg POINTS OUT.gpkg [options]

  HIER.gpkg      a hierarchy written by tinlod build (or a TIN of tinlod sample/insert),
                 or the catalogue of tinlod tiles
  POINTS         a point layer GDAL reads (its first layer); other CRSs are transformed;
                 a multipoint of one point counts, lines, polygons and multipoints of
                 several points are refused (one elevation per feature)
  OUT.gpkg       layer 'points': every feature of POINTS with its attributes, in its own
                 CRS, plus 'elevation' (metres) and 'triangle' (the id in the hierarchy's
                 'triangles' layer); both null for a point outside the TIN or in a hole

Options:
  -level L       the level whose TIN is interpolated: 0 the original, -1 the coarsest
                 (default 0)
  -overwrite     replace the 'points' layer of an existing GeoPackage
  -q             quiet: no progress or information, warnings only
)";

}  // namespace

int locateCommand(std::vector<std::string> args) {
  Arguments a(std::move(args));
  if (a.flag("--help") || a.flag("-h")) {
    std::cout << kHelp;
    return 0;
  }
  const int level = a.integer("-level", 0);
  const bool overwrite = a.flag("-overwrite");
  const bool quiet = a.flag("-q");
  const std::vector<std::string> files = a.operands(3, kUsage);
  const LocateSummary s = runLocateJob(files[0], files[1], files[2], level, overwrite, terminalFeedback(quiet));
  if (!quiet)
    std::cout << "Located " << s.located << " of " << s.points << " points on level " << s.level << " ("
              << s.points - s.located
              << (s.unfinishedTiles.empty() ? " outside the TIN or in holes; " : " outside the finished tiles' TIN or in holes; ")
              << s.seconds << " s"
              << (s.tilesRead ? "; " + std::to_string(s.tilesRead) + " tile reads" : "") << ") in " << files[2] << std::endl;
  return 0;
}

}  // namespace tinlod::cli
