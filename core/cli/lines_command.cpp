// SPDX-License-Identifier: GPL-3.0-or-later
#include <iostream>

#include "arguments.h"
#include "commands.h"
#include "terminal_feedback.h"
#include "tinlod/error.h"
#include "tinlod/line_layers.h"

namespace tinlod::cli {
namespace {

const char* const kUsage = "tinlod lines dp LINES OUT.gpkg [-threshold t] [-points] [-overwrite] [-q]";
const char* const kConcavityUsage =
    "tinlod lines concavity LINES OUT.gpkg -window d | -window_fraction f [-radius r] [-threshold t] [-overwrite] [-q]";

const char* const kHelp = R"(Tools for line layers (contours from gdal_contour, rivers, roads).

Usage: tinlod lines dp LINES OUT.gpkg [options]
       tinlod lines concavity LINES OUT.gpkg -window d [options]

dp: the Douglas-Peucker simplification value of every vertex, computed once so that any
threshold can be applied later: a line simplified at threshold t keeps the vertices whose
value exceeds t (the classic Douglas-Peucker simplification with tolerance t).

  LINES          the first layer of a vector file GDAL reads; each part of a multi-line is
                 a line. A layer in degrees is measured in the UTM zone of its centre.
  OUT.gpkg       layer 'lines' (LineStringM: M is each vertex's value in metres; the
                 endpoints, which every threshold keeps, have M = 1e300), with 'feature',
                 the source feature id

Options:
  -threshold t   also write layer 'simplified' (the lines at threshold t metres, t >= 0) and count
                 the pairs of segments of different simplified lines that meet (where
                 simplification makes contours cross; a crossing through a vertex counts
                 once per pair of segments there), stored as TINLOD_CROSSINGS
  -points        also write layer 'vertices' (Point: line, vertex, value; null for the
                 endpoints)
  -overwrite     replace these layers of an existing GeoPackage
  -q             quiet: no progress or information, warnings only

In QGIS a threshold can then be applied without recomputing, e.g. with the expression
m(point_n($geometry, n)) or by filtering the 'vertices' layer on "value" > t.

concavity: how each vertex bends, by two measures, and the lines cut into convex,
straight and concave parts. Positive values: the line bulges to its left (convex seen
from its left side); reversing a line flips the signs.

  -window d           secant measure: the points d metres along the line before and after
                      the vertex; the signed area between the line and their secant over
                      the secant's length squared (undefined within d of an end)
  -window_fraction f  the window as this share of each line's length (for lines simplified
                      to different degrees)
  -radius r           disk measure: the share of the disk of radius r around the vertex on
                      the line's left, minus one half, over one half, in [-1, 1] (default:
                      the window)
  -threshold t        parts: secant above t convex, below -t concave (default 0.02)
  OUT.gpkg            layers 'vertices' (Point: line, vertex, secant, disk; null where
                      undefined) and 'parts' (LineString: feature, class)
)";

int concavityTool(std::vector<std::string> args) {
  Arguments a(std::move(args));
  if (a.flag("--help") || a.flag("-h")) {
    std::cout << kHelp;
    return 0;
  }
  ConcavityOptions o;
  o.window = a.number("-window", 0);
  o.windowFraction = a.number("-window_fraction", 0);
  o.radius = a.number("-radius", 0);
  o.threshold = a.number("-threshold", o.threshold);
  const bool overwrite = a.flag("-overwrite");
  const bool quiet = a.flag("-q");
  const std::vector<std::string> files = a.operands(2, kConcavityUsage);
  const ConcavitySummary s = runConcavityJob(files[0], files[1], o, overwrite, terminalFeedback(quiet));
  if (!quiet)
    std::cout << "Wrote the concavity of " << s.vertices << " vertices of " << s.lines << " lines in " << s.crsName
              << " to " << files[1] << "\nParts: " << s.convex << " convex, " << s.straight << " straight, " << s.concave
              << " concave" << std::endl;
  return 0;
}

}  // namespace

int linesCommand(std::vector<std::string> args) {
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    std::cout << kHelp;
    return args.empty() ? 1 : 0;
  }
  if (args[0] == "concavity") return concavityTool(std::vector<std::string>(args.begin() + 1, args.end()));
  if (args[0] != "dp") throw Error("unknown lines tool '" + args[0] + "': the tools are dp and concavity (see tinlod lines --help)");
  Arguments a(std::vector<std::string>(args.begin() + 1, args.end()));
  if (a.flag("--help") || a.flag("-h")) {
    std::cout << kHelp;
    return 0;
  }
  DpOptions o;
  o.threshold = a.number("-threshold", o.threshold);
  o.points = a.flag("-points");
  const bool overwrite = a.flag("-overwrite");
  const bool quiet = a.flag("-q");
  const std::vector<std::string> files = a.operands(2, kUsage);
  const DpSummary s = runDpJob(files[0], files[1], o, overwrite, terminalFeedback(quiet));
  if (!quiet) {
    std::cout << "Wrote the Douglas-Peucker values of " << s.vertices << " vertices of " << s.lines << " lines in "
              << s.crsName << " to " << files[1] << "\n";
    if (o.threshold >= 0)
      std::cout << "At threshold " << o.threshold << " m: " << s.keptVertices << " vertices kept, " << s.crossings
                << " crossings between simplified lines\n";
    std::cout << std::flush;
  }
  return 0;
}

}  // namespace tinlod::cli
