// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the vertex and triangle layers shared by the TIN and the hierarchy files.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "gpkg_feature_rows.h"
#include "gpkg_output.h"
#include "packed_rtree.h"
#include "tinlod/tin.h"

namespace tinlod {

// id, row, col, outline; ids count from 1 and equal the fid.
std::vector<FieldSpec> vertexFields();
// id, v0, v1, v2 (vertex ids).
std::vector<FieldSpec> triangleFields();
std::vector<std::string> fieldNames(const std::vector<FieldSpec>& fields);

// `more` sets a layer's further fields of the i-th feature, after the common ones.
using MoreFields = std::function<void(GpkgFeatureRows&, std::size_t)>;

void writeVertices(const Tin& tin, GpkgFeatureRows& rows, std::int32_t srsId, const MoreFields& more,
                   const ProgressRange& progress);
// The rows alone, ids from `firstId` on, the layer left unfinished: for a writer that has
// the vertices a batch at a time (`more` is given the index in `vertices`).
void writeVertexRows(const std::vector<TinVertex>& vertices, std::int64_t firstId, GpkgFeatureRows& rows,
                     std::int32_t srsId, const MoreFields& more, const ProgressRange& progress);
// Corners of triangle i: the hierarchy's triangles are written without a copy of them.
using TriangleAt = std::function<const Triangle&(std::size_t)>;

void writeTriangles(const Tin& tin, std::size_t count, const TriangleAt& triangle, GpkgFeatureRows& rows,
                    std::int32_t srsId, const MoreFields& more, const ProgressRange& progress);
// The rows alone, ids from `firstId` on, the layer left unfinished: for a writer that has
// the triangles a batch at a time. Their corners index `vertices`; the vertex ids written
// are id[corner] + 1 (corner + 1 when `id` is empty).
void writeTriangleRows(const std::vector<TinVertex>& vertices, std::size_t count, const TriangleAt& triangle,
                       const std::vector<VertexId>& id, std::int64_t firstId, GpkgFeatureRows& rows, std::int32_t srsId,
                       const MoreFields& more, const ProgressRange& progress);

// The boxes of the layers' spatial indexes, in fid order.
std::vector<RtreeBox> vertexBoxes(const Tin& tin);
std::vector<RtreeBox> triangleBoxes(const Tin& tin, std::size_t count, const TriangleAt& triangle);
// The same added to `boxes`, of triangles whose corners index `vertices`.
void addTriangleBoxes(const std::vector<TinVertex>& vertices, std::size_t count, const TriangleAt& triangle,
                      std::vector<RtreeBox>& boxes);

}  // namespace tinlod
