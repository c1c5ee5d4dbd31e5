// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "tinlod/hierarchy_options.h"
#include "tinlod/level_survey.h"
#include "tinlod/tin.h"

namespace tinlod {

constexpr std::int32_t kNoGroup = -1;

// A triangle of some level: it appears at firstLevel and is replaced after lastLevel.
struct HierarchyTriangle {
  Triangle v{};                     // counter-clockwise
  std::int32_t group = kNoGroup;    // the group whose reject triangle it is (none at level 0)
  std::int32_t replacedBy = kNoGroup;  // the group whose accept triangle it is
  // Largest vertical distance to the DEM at the valid cell centres under it, rounded up to
  // a float: a bound read from it still holds.
  float error = 0;
  std::int16_t firstLevel = 0;
  std::int16_t lastLevel = 0;       // the coarsest level for triangles never replaced
};
// The hierarchy holds about five triangles a vertex, its largest array: 28 bytes each (the
// error as a float, the levels in 16 bits) is 20 bytes a vertex less than 32-bit levels:
// 40 MB for the 10 M triangles of a 4096 x 4096 tile.
static_assert(sizeof(HierarchyTriangle) == 28, "the hierarchy's largest array: keep it small");

// A distance as a HierarchyTriangle keeps it: the nearest float not below it (the
// simplifier's bounds on the DEM's cells are kept so too).
inline float roundedUpError(double d) {
  float f = static_cast<float>(d);
  if (double(f) < d) f = std::nextafter(f, INFINITY);
  return f;
}

// One deleted vertex: its star at the finer level (accept triangles) and the triangles
// that replaced it at the coarser level `level` (reject triangles).
struct Group {
  VertexId vertex = 0;
  std::int32_t level = 0;           // the coarser level: the vertex is in levels 0 .. level - 1
  double importance = 0;            // by the measure, when it was selected
  double error = 0;                 // largest vertical distance of the reject triangles to the DEM
  std::uint32_t acceptBegin = 0, acceptEnd = 0;  // ranges in Hierarchy::links
  std::uint32_t rejectBegin = 0, rejectEnd = 0;
  std::uint32_t ringBegin = 0, ringEnd = 0;      // the star's outline, in Hierarchy::rings
};

struct LevelStats {
  std::int32_t level = 0;
  std::size_t vertices = 0, triangles = 0, deleted = 0;
  double selectSeconds = 0, deleteSeconds = 0;
  // Against the DEM at every valid cell centre the level covers (a survey measures only
  // level 0: 0 above it):
  double maxError = 0;              // the largest vertical distance
  double rmse = 0;                  // the root mean square vertical distance
  std::int64_t cells = 0;           // how many valid cells it covers
  std::size_t outlineVertices = 0;  // vertices on the outline of the data or of a hole
};

// Kirkpatrick's hierarchy of TINs: level 0 is the original, each level above has an
// independent set of vertices deleted.
struct Hierarchy {
  Tin base;                                 // level 0 (vertices, triangles, CRS)
  std::vector<std::int32_t> vertexLevel;    // the highest level that contains each vertex
  std::vector<std::uint8_t> fixed;          // 1: never deleted
  std::vector<HierarchyTriangle> triangles; // every distinct triangle of every level
  std::vector<Group> groups;
  std::vector<std::uint32_t> links;         // triangle ids of the groups' accept and reject ranges (linkGroups)
  std::vector<VertexId> rings;              // vertex ids of the groups' outlines
  std::vector<LevelStats> levels;
  std::vector<LevelSurvey> survey;          // with HierarchyOptions::survey, by level from 1
  // A tile's line cells (globalCellKey) the border rule took but this tile's bound refused
  // (TileBorders::agreed): they stayed here, and must stay in the tile beyond the line too.
  std::vector<std::uint64_t> borderRefused;
  HierarchyOptions options;
  // How a file that is one TIN was made ("sample", "insert"); empty for a hierarchy,
  // whose method is options.measure.
  std::string tinMethod;
  // Why the simplification stopped before the stop percentage (empty when it reached it).
  std::string stopReason;

  std::int32_t coarsest() const { return static_cast<std::int32_t>(levels.size()) - 1; }
  // The triangles (indices into `triangles`) of one level.
  std::vector<std::uint32_t> levelTriangles(std::int32_t level) const;
  // One level as a TIN of its own vertices (renumbered) and triangles.
  Tin levelTin(std::int32_t level) const;
  std::pair<const std::uint32_t*, const std::uint32_t*> accept(const Group& g) const {
    return {links.data() + g.acceptBegin, links.data() + g.acceptEnd};
  }
  std::pair<const std::uint32_t*, const std::uint32_t*> reject(const Group& g) const {
    return {links.data() + g.rejectBegin, links.data() + g.rejectEnd};
  }
  // Whether accept and reject can be read: linkGroups has run (a hierarchy without
  // groups needs nothing).
  bool linked() const { return groups.empty() || !links.empty(); }
};

// Fills `links` and the groups' accept and reject ranges from the triangles' replacedBy
// and group, each range in triangle order: an index of what the triangles say, which
// extractLod and HierarchyLocator read. The reader makes it; buildHierarchy leaves it to
// its caller, since a hierarchy that is only written or measured never reads it.
void linkGroups(Hierarchy& h);

}  // namespace tinlod
