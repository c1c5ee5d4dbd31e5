// SPDX-License-Identifier: GPL-3.0-or-later
#include <iostream>
#include <limits>

#include "arguments.h"
#include "commands.h"
#include "terminal_feedback.h"
#include "tinlod/error.h"
#include "tinlod/lod_job.h"

namespace tinlod::cli {
namespace {

const char* const kUsage =
    "tinlod lod HIER.gpkg OUT.gpkg [-center X Y]... [-center_srs srs] [-centers POINTS] [-dropoff D] [-max_error E] [-error_growth G] "
    "[-region POLYGONS] [-vertex_index] [-overwrite] [-q]";

const char* const kHelp = R"(Extracts a TIN of varying level of detail from a hierarchy (tinlod build): fine near
the centres of detail, in a region or where the terrain needs it, coarse elsewhere; one
conforming TIN (de Berg and Dobrindt's traversal of the hierarchy).

Usage: tinlod lod HIER.gpkg OUT.gpkg [tests] [options]

  HIER.gpkg          a hierarchy written by tinlod build, or the catalogue of tinlod tiles
                     (its finished tiles as one hierarchy, one TIN across them; read a tile at a time)
  OUT.gpkg           GeoPackage TIN: 'vertices' (PointZ: id, row, col, outline, level) and
                     'triangles' (PolygonZ: id, v0, v1, v2, first_level, last_level), in
                     the hierarchy's CRS

Tests (a deleted vertex is restored when any given test accepts it):
  -dropoff D         the study's distance test: a vertex deleted at level L is restored
                     when it is closer than L x D metres to a centre of detail
  -max_error E       the error test: restored while the triangles that replaced it are
                     more than E metres (vertically) from the DEM at a valid cell centre
                     under them (level 0's own triangles are as fine as it gets) ...
  -error_growth G    ... plus G metres per metre of distance to the nearest centre
  -region POLYGONS   every vertex whose replacing triangles meet the polygons of this
                     vector file is restored: full detail there, coarse outside

Centres of detail (in the hierarchy's CRS; other CRSs of a file are transformed):
  -center X Y        a centre; repeat it for several
  -center_srs srs    the CRS of every -center (EPSG:4326: longitude latitude; any GDAL
                     definition), transformed to the hierarchy's (default: the hierarchy's)
  -centers POINTS    every point of this vector file is a centre (each point of a
                     multipoint too; lines and polygons are refused)

  -vertex_index      also give the vertices layer a spatial index (about 37 bytes a
                     vertex), for drawing it zoomed in
  -overwrite         replace tinlod's layers of an existing GeoPackage
  -q                 quiet: no progress or information, warnings only

A vertex a restored vertex needs (a coarser neighbour whose triangles hold its star) is
restored as well, so every test holds everywhere and the TIN conforms. With -dropoff 0
the TIN is the coarsest level; with a dropoff larger than the terrain it is level 0.
)";

}  // namespace

int lodCommand(std::vector<std::string> args) {
  Arguments a(std::move(args));
  if (a.flag("--help") || a.flag("-h")) {
    std::cout << kHelp;
    return 0;
  }
  LodJobOptions o;
  for (const std::vector<double>& c : a.repeatedNumbers("-center", 2)) o.lod.centres.push_back({c[0], c[1]});
  o.centresSrs = a.text("-center_srs", "");
  if (!o.centresSrs.empty() && o.lod.centres.empty()) throw Error("-center_srs is the CRS of -center: give -center X Y too");
  o.centresPath = a.text("-centers", "");
  o.regionPath = a.text("-region", "");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  o.lod.dropoff = a.number("-dropoff", nan);
  o.lod.maxError = a.number("-max_error", nan);
  o.lod.errorGrowth = a.number("-error_growth", 0);
  const bool vertexIndex = a.flag("-vertex_index");
  const bool overwrite = a.flag("-overwrite");
  const bool quiet = a.flag("-q");
  const std::vector<std::string> files = a.operands(2, kUsage);
  const LodSummary s = runLodJob(files[0], files[1], o, overwrite, terminalFeedback(quiet), vertexIndex);
  if (!quiet) {
    std::cout << "Wrote " << s.triangles << " triangles and " << s.vertices << " vertices (level 0 has "
              << s.levelZeroTriangles << " triangles; extraction alone in " << s.seconds
              << " s, reading and writing aside) in " << s.crsName << " to "
              << files[1] << "\nTriangles by the finest level they are in (first_level):";
    for (std::size_t L = 0; L < s.trianglesPerLevel.size(); ++L)
      if (s.trianglesPerLevel[L]) std::cout << " " << L << ": " << s.trianglesPerLevel[L];
    std::cout << std::endl;
  }
  return 0;
}

}  // namespace tinlod::cli
