// SPDX-License-Identifier: GPL-3.0-or-later
#include <cctype>
#include <filesystem>
#include <iostream>

#include "arguments.h"
#include "commands.h"
#include "terminal_feedback.h"
#include "tinlod/error.h"
#include "tinlod/synthetic_dem.h"

namespace tinlod::cli {
namespace {

const char* const kUsage = "tinlod makedem OUT.tif [-size width height] [-cell m] [-seed n] [-no_void] [-no_lake] [-overwrite] [-q]";

const char* const kHelp = R"(Writes the project's default DEM (with the default options): a synthetic terrain of fractal hills and a
ridge, with an exactly flat lake and a nodata void, in UTM zone 32N (Float32 GeoTIFF,
nodata -9999). Real DEMs are not shipped with tinlod; this one needs no download.

Usage: tinlod makedem OUT.tif [options]

  -size w h      cells across and down (default 1200 1000)
  -cell m        cell size in metres, more than 0 and at most 1000 (default 20)
  -seed n        terrain seed (default 7)
  -no_void       no nodata hole
  -no_lake       no flat lake
  -overwrite     replace OUT.tif if it exists
  -q             quiet
)";

}  // namespace

int makeDemCommand(std::vector<std::string> args) {
  Arguments a(std::move(args));
  if (a.flag("--help") || a.flag("-h")) {
    std::cout << kHelp;
    return 0;
  }
  SyntheticDemOptions o;
  const std::vector<int> size = a.integers("-size", 2, {o.width, o.height});
  o.width = size[0];
  o.height = size[1];
  o.cellSize = a.number("-cell", o.cellSize);
  o.seed = a.unsignedInteger("-seed", o.seed);
  o.withVoid = !a.flag("-no_void");
  o.withLake = !a.flag("-no_lake");
  const bool overwrite = a.flag("-overwrite");
  const bool quiet = a.flag("-q");
  const std::vector<std::string> files = a.operands(1, kUsage);
  std::string extension = std::filesystem::path(files[0]).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (extension != ".tif" && extension != ".tiff")
    throw Error("output '" + files[0] + "' must be a GeoTIFF file ending in .tif");
  if (o.width < 2 || o.height < 2 || double(o.width) * o.height > 1e8)
    throw Error("-size must be at least 2 x 2 and at most 100 million cells");
  // Larger cells would take the terrain's tilt past any real height, and huge ones past a double.
  if (!(o.cellSize > 0 && o.cellSize <= 1000))
    throw Error("-cell must be more than 0 and at most 1000 metres");
  const ProgressRange all(terminalFeedback(quiet), 0, 1);
  writeDemGeoTiff(makeSyntheticDem(o, all.sub(0, 0.5)), files[0], overwrite, all.sub(0.5, 1));
  all.finish("Done");
  if (!quiet)
    std::cout << "Wrote a synthetic DEM (" << o.width << " x " << o.height << " cells of " << o.cellSize
              << " m) to " << files[0] << std::endl;
  return 0;
}

}  // namespace tinlod::cli
