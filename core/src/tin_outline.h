// SPDX-License-Identifier: GPL-3.0-or-later
// Private: which vertices of a TIN lie on its outline (the raster's edge, a hole's), as its
// triangles say it. The sampler's `outline` flag says something else: a cell on the outline
// of the valid cells, which it takes whole; beside a hole's stair-steps many of those end
// inside the TIN.
#pragma once

#include <cstddef>
#include <vector>

#include "tinlod/tin.h"

namespace tinlod {

// For each vertex: whether it is on an edge that only one triangle has. A vertex in no
// triangle is not.
std::vector<bool> outlineVertices(const Tin& tin);

std::size_t countOutlineVertices(const Tin& tin);

}  // namespace tinlod
