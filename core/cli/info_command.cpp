// SPDX-License-Identifier: GPL-3.0-or-later
#include <iostream>

#include "arguments.h"
#include "commands.h"
#include "tinlod/hierarchy_info.h"

namespace tinlod::cli {

int infoCommand(std::vector<std::string> args) {
  Arguments a(std::move(args));
  if (a.flag("--help") || a.flag("-h")) {
    std::cout << "Describes a GeoPackage written by tinlod build, sample, insert or lod: parameters, CRS,\n"
                 "size, and per level the vertices, triangles, deleted vertices, times and maximum\n"
                 "vertical error. Given a tinlod tiles catalogue, also its tiles by status (the failed\n"
                 "ones with their errors) and its finished tiles' levels added up; a finished tile it\n"
                 "cannot read is named, the rest described, and the exit code is 1.\n\n"
                 "Usage: tinlod info FILE.gpkg [-json]\n";
    return 0;
  }
  const bool json = a.flag("-json");
  const std::vector<std::string> files = a.operands(1, "tinlod info FILE.gpkg [-json]");
  const HierarchyInfo info = readHierarchyInfo(files[0]);
  std::cout << (json ? toJson(info) : toText(info));
  // Described all the same, but a script must not take the levels for the whole catalogue's.
  if (!info.unreadableTiles.empty()) {
    std::cout.flush();
    std::cerr << "ERROR: " << info.unreadableTiles.size() << " of the catalogue's finished tiles cannot be read (the "
              << "levels above leave them out): " << info.unreadableTiles.front() << std::endl;
    return 1;
  }
  return 0;
}

}  // namespace tinlod::cli
