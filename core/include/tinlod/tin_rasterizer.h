// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <vector>

#include "tinlod/feedback.h"
#include "tinlod/grid.h"
#include "tinlod/tin.h"

namespace tinlod {

// Linear interpolation of a TIN at the test points: each triangle fills the points it
// covers with its plane (far faster than locating every point). `positions` are the
// vertices in test-point units (see gridPositions), `z` their heights, `triangles`
// index both. Points no triangle covers stay NaN; a point on a shared edge takes
// either triangle's value, which agree there (to the last bit or so: the later one's, in
// the triangles' order among those whose tops lie in one row). The grid is `cols` x `rows`
// points from point (col0, row0) of the positions' grid: a window of a larger grid, whose
// values are computed exactly as the larger grid's are.
Grid rasterizeTin(const std::vector<std::array<double, 2>>& positions, const std::vector<double>& z,
                  const std::vector<Triangle>& triangles, int cols, int rows, const ProgressRange& progress,
                  int col0 = 0, int row0 = 0);

}  // namespace tinlod
