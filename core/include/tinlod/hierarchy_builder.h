// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "tinlod/feedback.h"
#include "tinlod/hierarchy.h"

namespace tinlod {

using PointXY = std::array<double, 2>;

// Simplifies `base` level by level into a hierarchy. Vertices flagged in `fixed`, the
// vertices nearest to `keep` (points in the TIN's CRS; points off the TIN's data are
// ignored with a warning), and every vertex on the TIN's outline or on the edge of a
// hole are never deleted: the extent and the holes are the same at every level. The
// hierarchy keeps `base`: pass std::move(tin) when the TIN is not needed afterwards.
Hierarchy buildHierarchy(Tin base, std::vector<std::uint8_t> fixed, const HierarchyOptions& options,
                         const ProgressRange& progress, const std::vector<PointXY>& keep = {});

}  // namespace tinlod
