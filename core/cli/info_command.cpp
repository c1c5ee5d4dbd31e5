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
                 "ones with their errors) and its finished tiles' levels added up.\n\n"
                 "Usage: tinlod info FILE.gpkg [-json]\n";
    return 0;
  }
  const bool json = a.flag("-json");
  const std::vector<std::string> files = a.operands(1, "tinlod info FILE.gpkg [-json]");
  const HierarchyInfo info = readHierarchyInfo(files[0]);
  std::cout << (json ? toJson(info) : toText(info));
  return 0;
}

}  // namespace tinlod::cli
