// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tinlod {

// What a hierarchy GeoPackage holds beside what every reader needs (vertices, triangles,
// the groups' links and the levels table): the user chooses by what they will look at.
struct HierarchyLayers {
  // The level_N views written; empty means all. kCoarsest stands for the last level.
  std::vector<std::int32_t> levelViews;
  static constexpr std::int32_t kCoarsest = -1;
  // The groups' outline polygons (2D). Without them the groups layer is a plain table: the
  // file is still a whole hierarchy for lod, locate and accuracy.
  bool groupOutlines = true;
  // A spatial index on the vertices layer, for drawing it zoomed in. Nothing in tinlod
  // reads vertices by place, and it costs 7 bytes a stored triangle.
  bool vertexIndex = false;

  // The levels of views to write for a hierarchy of levels 0..coarsest, ascending and
  // without repeats; levels above the coarsest are left out (see missingLevels).
  std::vector<std::int32_t> views(std::int32_t coarsest) const;
  std::vector<std::int32_t> missingLevels(std::int32_t coarsest) const;
};

// "all", or levels separated by commas, "last" for the coarsest: "0,5,last". Throws Error
// naming `option` on anything else.
std::vector<std::int32_t> parseLevelList(const std::string& text, const std::string& option);
std::string levelListText(const std::vector<std::int32_t>& levels);

}  // namespace tinlod
