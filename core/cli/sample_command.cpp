// SPDX-License-Identifier: GPL-3.0-or-later
#include <iostream>

#include "arguments.h"
#include "commands.h"
#include "sample_arguments.h"
#include "terminal_feedback.h"
#include "tinlod/sample_job.h"

namespace tinlod::cli {
namespace {

const char* const kUsage = "tinlod sample DEM OUT.gpkg [-b band] [-s_srs srs] [-t_srs srs] [-block k] [-jitter m] [-seed n] [-valid_range min max] [-vertex_index] [-overwrite] [-q]";

const char* const kHelp = R"(Samples a DEM into a Delaunay TIN and writes it to a GeoPackage.

Usage: tinlod sample DEM OUT.gpkg [options]

  DEM            any raster GDAL reads (GeoTIFF, SRTM .hgt, ENVI .bil, ASCII grid, VRT ...)
  OUT.gpkg       GeoPackage with layers 'vertices' (PointZ: id, row, col, outline) and
                 'triangles' (PolygonZ, one feature per triangle: id, v0, v1, v2); ids
                 equal the features' fid, so v0, v1, v2 join to vertices.fid

Options:
  -b band        band holding the heights (default 1)
  -s_srs srs     CRS of the DEM, for a file with none or a wrong one (e.g. an .asc grid
                 in degrees without .prj: -s_srs EPSG:4326)
  -t_srs srs     metric CRS of the TIN, e.g. EPSG:32632 (default: the DEM's own CRS if it
                 is in metres, else the UTM zone of the DEM's centre)
  -block k       one random valid cell per k x k block (default 3, as in the study; 1 takes
                 every cell). The outline of the valid area is always taken whole.
  -jitter m      x and y of each point moved by a random offset in [0, m) metres so that no
                 four points are cocircular (default 0.99); must be less than the cell
                 size, and is best well under half of it (e.g. 0.1 for 1 m LiDAR)
  -seed n        random seed; the same seed gives the same TIN (default 1)
  -valid_range min max
                 heights outside min..max metres are nodata, counted in one warning
                 (default -12000 9000, the Earth's range: undeclared fill values such as
                 1e30, -32768 or infinity never become vertices)
  -vertex_index  also give the vertices layer a spatial index (about 37 bytes a vertex),
                 for drawing it zoomed in; nothing in tinlod reads the vertices by place
  -overwrite     replace the 'vertices' and 'triangles' layers of an existing GeoPackage;
                 its other layers are kept
  -q             quiet: no progress or information, warnings only

Nodata cells (declared nodata, NaN, masks, heights outside -valid_range) never become
vertices, and no triangle spans them: holes stay holes. A band of complex numbers is refused. Heights are never resampled (band scale and offset are applied,
heights in feet converted to metres); a geographic DEM only has its points' x and y
transformed to metres. Ctrl-C stops the run and leaves no file behind.
)";

}  // namespace

int sampleCommand(std::vector<std::string> args) {
  Arguments a(std::move(args));
  if (a.flag("--help") || a.flag("-h")) {
    std::cout << kHelp;
    return 0;
  }
  const SampleOptions options = sampleOptions(a);
  const bool vertexIndex = a.flag("-vertex_index");
  const bool overwrite = a.flag("-overwrite");
  const bool quiet = a.flag("-q");
  const std::vector<std::string> files = a.operands(2, kUsage);

  const SampleSummary s = runSampleJob(files[0], files[1], options, overwrite, terminalFeedback(quiet), vertexIndex);
  if (!quiet)
    std::cout << "Wrote " << s.vertices << " vertices and " << s.triangles << " triangles ("
              << s.outlineVertices << " vertices on the outline) covering " << s.area / 1e6
              << " km2 in " << s.crsName << " to " << files[1] << std::endl;
  return 0;
}

}  // namespace tinlod::cli
