// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "tinlod/hierarchy.h"

namespace tinlod {

// What a tinlod GeoPackage says of itself, for `tinlod info`.
struct HierarchyInfo {
  std::string path;
  std::string kind;  // "hierarchy" or "tin"
  std::string crsName;
  std::uintmax_t bytes = 0;
  std::map<std::string, std::string> metadata;  // TINLOD_* items, without the prefix, lower case
  std::vector<LevelStats> levels;                // one for a plain TIN
  std::vector<std::string> layers;
};

// Throws Error when the file is not a GeoPackage made by tinlod.
HierarchyInfo readHierarchyInfo(const std::string& path);

std::string toJson(const HierarchyInfo& info);
std::string toText(const HierarchyInfo& info);

}  // namespace tinlod
