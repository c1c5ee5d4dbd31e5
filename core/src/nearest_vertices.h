// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the TIN vertex nearest to each of some points, for points to keep.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "tinlod/feedback.h"
#include "tinlod/tin.h"

namespace tinlod {

// For each point (x, y in the TIN's CRS) that falls on one of the TIN's triangles, the
// vertex nearest to it, among those `excluded` does not mark (by vertex; empty: all);
// points off the triangles (outside, or in a hole) are left out and counted in `off`.
std::vector<VertexId> nearestVerticesOnData(const Tin& tin, const std::vector<std::array<double, 2>>& points,
                                            std::size_t& off, const ProgressRange& progress,
                                            const std::vector<std::uint8_t>& excluded = {});

}  // namespace tinlod
