// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "tinlod/feedback.h"
#include "tinlod/hierarchy.h"

namespace tinlod {

// Which deleted vertices a varying level-of-detail TIN restores. A vertex is restored
// when any test given accepts it.
struct LodOptions {
  std::vector<std::array<double, 2>> centres;  // centres of detail, in the hierarchy's CRS
  // The study's distance test: restore a vertex deleted at level L when its distance to
  // the nearest centre is below L x dropoff (metres). NaN: no distance test.
  double dropoff = std::numeric_limits<double>::quiet_NaN();
  // The error test: restore a vertex while the error of the triangles that replaced it
  // exceeds maxError + errorGrowth x its distance to the nearest centre (no centre: the
  // tolerance is maxError everywhere). NaN: no error test.
  double maxError = std::numeric_limits<double>::quiet_NaN();
  double errorGrowth = 0;  // metres of tolerance per metre of distance
  // The region test: restore every vertex one of whose replacing triangles (corners given)
  // meets the region, so that every triangle of the result that meets it is of level 0.
  std::function<bool(const std::array<std::array<double, 2>, 3>& triangle)> meetsRegion;
  void validate() const;   // throws Error naming the option
};

// De Berg and Dobrindt's traversal: from the coarsest level down, a group's reject
// triangles are replaced by its accept triangles when its vertex is accepted. So that
// every accepted vertex can be restored, a group is also refined when a finer accepted
// group needs one of its accept triangles (the study's traversal would leave such a
// vertex out). Returns the triangles (indices into h.triangles) of a conforming TIN
// covering exactly what every level covers.
//
// `vertices`, when given, says which vertices must come back whatever the tests say
// (`forced`, one flag per vertex, or empty for none) and gets every vertex that comes back
// (`back`): the tiles of a catalogue, each extracted on its own, bring a vertex of the line
// two tiles share back when either does.
struct LodVertices {
  std::vector<std::uint8_t> forced;
  std::vector<std::uint8_t> back;
};
std::vector<std::uint32_t> extractLod(const Hierarchy& h, const LodOptions& options, const ProgressRange& progress,
                                      LodVertices* vertices = nullptr);

}  // namespace tinlod
