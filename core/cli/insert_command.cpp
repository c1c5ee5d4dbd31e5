// SPDX-License-Identifier: GPL-3.0-or-later
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>

#include "arguments.h"
#include "commands.h"
#include "sample_arguments.h"
#include "terminal_feedback.h"
#include "tinlod/error.h"
#include "tinlod/insert_job.h"

namespace tinlod::cli {
namespace {

const char* const kUsage =
    "tinlod insert DEM OUT.gpkg [-max_error m] [-max_vertices n] [-max_triangles n] [-candidates cells|samples] [-delaunay ground|grid] "
    "[-b band] [-s_srs srs] [-t_srs srs] [-block k] [-jitter m] [-seed n] [-valid_range min max] [-vertex_index] [-overwrite] [-q]";

const char* const kHelp = R"(Greedy insertion (Garland and Heckbert): a TIN from a DEM by inserting, again and
again, the point of largest vertical error, until every point is within a tolerance.

Usage: tinlod insert DEM OUT.gpkg [options]

  DEM            any raster GDAL reads
  OUT.gpkg       GeoPackage with the layers of 'tinlod sample': 'vertices' (PointZ: id, row,
                 col, outline, insertion, error_before) and 'triangles' (PolygonZ: id, v0,
                 v1, v2). 'insertion' is the vertex's place in the insertion order: the
                 vertices with insertion <= k make a coarser TIN (a progressive TIN) whose
                 maximum error is the error_before of vertex k + 1 (null for the starting
                 hull and for vertices placed to keep triangles off nodata holes).

Stopping (whichever comes first):
  -max_error m      every candidate within m metres of the TIN, vertically (default 1;
                    0 inserts until the TIN is exact). With only -max_vertices or
                    -max_triangles given, the default is 0: the count alone stops it.
  -max_vertices n   at most n vertices: exactly n unless the tolerance is met first or
                    the DEM has holes (vertices left in no triangle beside a hole are
                    dropped); 0: no limit (default)
  -max_triangles n  at most n triangles; 0: no limit (default)

Options:
  -candidates c  'cells' (default): every valid DEM cell may become a vertex, the last row
                 and column included; 'samples': only the vertices of the TIN that
                 'tinlod sample' makes with the same -block, -jitter and -seed (the
                 study's comparison with the delete methods on the same input)
  -delaunay d    'ground' (default): the TIN is Delaunay in metres on the ground; 'grid':
                 Delaunay on the DEM's grid with square cells, as delatin and most tools
                 do. They differ only where cells are not square on the ground (a
                 geographic DEM away from the equator), by a few % of vertices either way.
  -b band        band holding the heights (default 1)
  -valid_range min max
                 heights outside min..max metres are nodata (default -12000 9000)
  -s_srs srs     CRS of the DEM, for a file with none or a wrong one
  -t_srs srs     metric CRS of the TIN (default: the DEM's own if in metres, else UTM)
  -block k, -jitter m, -seed n   sampling of the 'samples' candidates (as 'tinlod sample');
                 not used with 'cells'
  -vertex_index  also give the vertices layer a spatial index (about 37 bytes a vertex),
                 for drawing it zoomed in; nothing in tinlod reads the vertices by place
  -overwrite     replace tinlod's layers of an existing GeoPackage; its other layers are kept
  -q             quiet: no progress or information, warnings only

The run starts from the convex hull of the valid cells (the corners of a full raster) at
their own heights and keeps the TIN Delaunay in metres on the ground (also for a
geographic DEM, whose TIN is written in a UTM zone). No triangle spans a nodata hole:
triangles over a hole's edge are split along it first. The maximum error and RMSE are
measured again at every valid cell after the run, printed and stored in the file's
metadata. Ctrl-C stops the run and leaves no file behind.
)";

InsertOptions insertOptions(Arguments& a) {
  InsertOptions o;
  const bool sampling = a.given("-block") || a.given("-jitter") || a.given("-seed");
  o.sample = sampleOptions(a);
  o.candidates = parseCandidates(a.text("-candidates", "cells"));
  if (sampling && o.candidates == InsertCandidates::Cells)
    terminalFeedback(true).warning("-block, -jitter and -seed sample the candidates of -candidates samples; with every "
                                   "cell a candidate (the default) they are unused");
  const std::string delaunay = a.text("-delaunay", "ground");
  if (delaunay != "ground" && delaunay != "grid")
    throw Error("-delaunay must be 'ground' (in metres, the default) or 'grid' (square cells), not '" + delaunay + "'");
  o.delaunayOnGrid = delaunay == "grid";
  const double maxError = a.number("-max_error", std::numeric_limits<double>::quiet_NaN());
  const double maxVertices = a.number("-max_vertices", 0), maxTriangles = a.number("-max_triangles", 0);
  // Past 2^53 a double holds no odd whole numbers, and past 2^64 the count would not convert.
  const double most = 9007199254740992.0;
  if (maxVertices < 0 || maxVertices != std::floor(maxVertices) || maxTriangles < 0 || maxTriangles != std::floor(maxTriangles) ||
      maxVertices > most || maxTriangles > most)
    throw Error("-max_vertices and -max_triangles take whole numbers from 0 to 2^53 (9007199254740992)");
  o.maxVertices = static_cast<std::size_t>(maxVertices);
  o.maxTriangles = static_cast<std::size_t>(maxTriangles);
  o.maxError = !std::isnan(maxError) ? maxError : (o.maxVertices || o.maxTriangles) ? 0 : 1;
  return o;
}

void printSummary(const InsertSummary& s, const InsertOptions& o, const std::string& out) {
  std::cout << "Wrote " << s.vertices << " vertices and " << s.triangles << " triangles (from " << s.candidates
            << " candidates; insertion " << s.seconds << " s) in " << s.crsName << " to " << out << "\n";
  if (o.candidates == InsertCandidates::Samples && std::isfinite(s.maxError))
    std::cout << "Maximum error at the sampled candidates (where the tolerance applies) " << s.maxError
              << " m; against every DEM cell, maximum error ";
  else
    std::cout << "Maximum error ";
  std::cout << std::setprecision(10) << s.measuredMaxError << std::setprecision(6) << " m, RMSE "
            << s.rmse << " m over " << s.measuredCells << " cells";
  if (s.uncoveredCells)
    std::cout << " (" << s.uncoveredCells << (s.uncoveredCells == 1 ? " valid cell" : " valid cells")
              << (s.holesOpen ? " in no triangle: the limit came before the TIN was cut free of the holes)"
                  : o.candidates == InsertCandidates::Cells
                      ? " in no triangle: data one cell wide beside nodata)"
                      // The sampled TIN covers every valid cell but thin data's: the rest is the
                      // limit's, with triangles beside a hole still spanning it, dropped.
                      : " in no triangle: data too thin for one beside nodata, or beside a hole whose outline the limit "
                        "left unfinished)");
  std::cout << std::endl;
}

}  // namespace

int insertCommand(std::vector<std::string> args) {
  Arguments a(std::move(args));
  if (a.flag("--help") || a.flag("-h")) {
    std::cout << kHelp;
    return 0;
  }
  const InsertOptions options = insertOptions(a);
  const bool vertexIndex = a.flag("-vertex_index");
  const bool overwrite = a.flag("-overwrite");
  const bool quiet = a.flag("-q");
  const std::vector<std::string> files = a.operands(2, kUsage);

  const InsertSummary s = runInsertJob(files[0], files[1], options, overwrite, terminalFeedback(quiet), vertexIndex);
  if (!quiet) printSummary(s, options, files[1]);
  return 0;
}

}  // namespace tinlod::cli
