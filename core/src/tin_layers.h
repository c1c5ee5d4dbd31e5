// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the vertex and triangle layers shared by the TIN and the hierarchy files.
#pragma once

#include <functional>
#include <vector>

#include "gpkg_output.h"
#include "tinlod/tin.h"

namespace tinlod {

// id, row, col, outline; ids count from 1 and equal the fid.
std::vector<FieldSpec> vertexFields();
// id, v0, v1, v2 (vertex ids).
std::vector<FieldSpec> triangleFields();

// `more` sets a layer's further fields of the i-th feature, after the common ones.
using MoreFields = std::function<void(OGRFeature&, std::size_t)>;

void writeVertices(const Tin& tin, OGRLayer& layer, const MoreFields& more, const ProgressRange& progress);
void writeTriangles(const Tin& tin, const std::vector<Triangle>& triangles, OGRLayer& layer, const MoreFields& more,
                    const ProgressRange& progress);

}  // namespace tinlod
