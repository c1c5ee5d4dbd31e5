// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstdint>
#include <vector>

#include "tinlod/feedback.h"
#include "tinlod/hierarchy.h"

namespace tinlod {

// Simplifies `base` level by level into a hierarchy. Vertices flagged in `fixed`, and
// every vertex on the TIN's outline or on the edge of a hole, are never deleted: the
// extent and the holes are the same at every level.
Hierarchy buildHierarchy(const Tin& base, std::vector<std::uint8_t> fixed, const HierarchyOptions& options,
                         const ProgressRange& progress);

}  // namespace tinlod
