// SPDX-License-Identifier: GPL-3.0-or-later
// The tinlod command line: a thin adapter over the core library, in the manner of
// GDAL's utilities (exit 0 on success, 1 with "ERROR: ..." otherwise).
#include <gdal_priv.h>

#include <exception>
#include <iostream>
#include <map>

#include "commands.h"
#include "terminal_feedback.h"
#include "tinlod/allocator_policy.h"
#include "tinlod/error.h"
#include "tinlod/version.h"

namespace {

const char* const kHelp = R"(tinlod: simplified, hierarchical TINs from raster DEMs

Usage: tinlod COMMAND [options]   (tinlod COMMAND --help for its options)

Commands:
  build       sample a DEM and simplify it into a TIN hierarchy, written to a GeoPackage
  accuracy    measure the accuracy of every level of a hierarchy: raster and report
  experiment  run the study's experiment over DEMs: methods x delete percentages, one report
  insert      greedy insertion (Garland and Heckbert): a TIN within a vertical tolerance
  lod         extract a TIN of varying level of detail from a hierarchy
  lines       tools for line layers: Douglas-Peucker values (dp), concavity
  locate      the elevation at points, located through the hierarchy
  info        describe a GeoPackage written by tinlod
  sample      sample a DEM into a Delaunay TIN, written to a GeoPackage
  makedem     write the project's synthetic default DEM (a GeoTIFF)
  tiles       build a DEM of any size as tiles with Dask, listed in a catalogue (tinlod-tiles)

  --version   print the version
)";

using Command = int (*)(std::vector<std::string>);

}  // namespace

int main(int argc, char** argv) {
  tinlod::mapLargeArraysApart();
  const std::map<std::string, Command> commands{{"accuracy", tinlod::cli::accuracyCommand},
                                                 {"build", tinlod::cli::buildCommand},
                                                 {"experiment", tinlod::cli::experimentCommand},
                                                 {"info", tinlod::cli::infoCommand},
                                                 {"insert", tinlod::cli::insertCommand},
                                                 {"lines", tinlod::cli::linesCommand},
                                                 {"locate", tinlod::cli::locateCommand},
                                                 {"lod", tinlod::cli::lodCommand},
                                                 {"sample", tinlod::cli::sampleCommand},
                                                 {"makedem", tinlod::cli::makeDemCommand},
                                                 {"tiles", tinlod::cli::tilesCommand}};
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    std::cout << kHelp;
    return argc < 2 ? 1 : 0;
  }
  const std::string name = argv[1];
  if (name == "--version") {
    std::cout << "tinlod " << tinlod::kVersion << " (GDAL " << GDALVersionInfo("RELEASE_NAME") << ")\n";
    return 0;
  }
  // `tinlod help` and `tinlod help build`, as git and gdal users type them.
  if (name == "help") {
    const auto asked = argc > 2 ? commands.find(argv[2]) : commands.end();
    if (asked == commands.end()) {
      std::cout << kHelp;
      return argc > 2 ? 1 : 0;
    }
    return asked->second({"--help"});
  }
  const auto command = commands.find(name);
  if (command == commands.end()) {
    std::cerr << "ERROR: unknown command '" << name << "'\n" << kHelp;
    return 1;
  }
  try {
    return command->second(std::vector<std::string>(argv + 2, argv + argc));
  } catch (const tinlod::Cancelled&) {
    tinlod::cli::breakProgressLine();
    std::cerr << "ERROR: stopped before the end; nothing was written" << std::endl;
    return 130;  // as a shell reports a run ended by Ctrl-C
  } catch (const tinlod::EmptyTile& e) {
    tinlod::cli::breakProgressLine();
    std::cerr << "NOTE: " << e.what() << "; nothing was written" << std::endl;
    return 3;  // not a failure: a tiled run records the tile as empty
  } catch (const std::exception& e) {
    tinlod::cli::breakProgressLine();
    std::cerr << "ERROR: " << e.what() << std::endl;
    return 1;
  }
}
