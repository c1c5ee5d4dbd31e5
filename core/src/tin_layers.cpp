// SPDX-License-Identifier: GPL-3.0-or-later
#include "tin_layers.h"

namespace tinlod {

std::vector<FieldSpec> vertexFields() {
  return {{"id"}, {"row"}, {"col"}, {"outline", OFTInteger, OFSTBoolean}};
}

std::vector<FieldSpec> triangleFields() { return {{"id"}, {"v0"}, {"v1"}, {"v2"}}; }

std::vector<std::string> fieldNames(const std::vector<FieldSpec>& fields) {
  std::vector<std::string> names;
  for (const FieldSpec& f : fields) names.emplace_back(f.name);
  return names;
}

void writeVertices(const Tin& tin, GpkgFeatureRows& rows, std::int32_t srsId, const MoreFields& more,
                   const ProgressRange& progress) {
  writeVertexRows(tin.vertices, 1, rows, srsId, more, progress);
  rows.finish();
}

void writeVertexRows(const std::vector<TinVertex>& vertices, std::int64_t firstId, GpkgFeatureRows& rows,
                     std::int32_t srsId, const MoreFields& more, const ProgressRange& progress) {
  GpkgGeometryBlob point(srsId);
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const TinVertex& v = vertices[i];
    const std::int64_t id = firstId + static_cast<std::int64_t>(i);
    rows.set(0, id);
    rows.set(1, v.row);
    rows.set(2, v.col);
    rows.set(3, v.outline ? 1 : 0);
    if (more) more(rows, i);
    point.pointZ(v.x, v.y, v.z);
    rows.insert(id, point);
    if ((i & 0x3FFF) == 0) progress.report(double(i) / vertices.size(), "Writing vertices");
  }
}

void writeTriangles(const Tin& tin, std::size_t count, const TriangleAt& triangle, GpkgFeatureRows& rows,
                    std::int32_t srsId, const MoreFields& more, const ProgressRange& progress) {
  writeTriangleRows(tin.vertices, count, triangle, {}, 1, rows, srsId, more, progress);
  rows.finish();
}

void writeTriangleRows(const std::vector<TinVertex>& vertices, std::size_t count, const TriangleAt& triangle,
                       const std::vector<VertexId>& id, std::int64_t firstId, GpkgFeatureRows& rows, std::int32_t srsId,
                       const MoreFields& more, const ProgressRange& progress) {
  GpkgGeometryBlob polygon(srsId);
  for (std::size_t i = 0; i < count; ++i) {
    const Triangle& t = triangle(i);
    const std::int64_t fid = firstId + static_cast<std::int64_t>(i);
    rows.set(0, fid);
    for (int k = 0; k < 3; ++k) rows.set(k + 1, static_cast<std::int64_t>(id.empty() ? t[k] : id[t[k]]) + 1);
    if (more) more(rows, i);
    polygon.polygon(3, [&](std::size_t k, double& x, double& y, double& z) {
      const TinVertex& v = vertices[t[k]];
      x = v.x, y = v.y, z = v.z;
    }, true);
    rows.insert(fid, polygon);
    if ((i & 0x3FFF) == 0) progress.report(double(i) / count, "Writing triangles");
  }
}

std::vector<RtreeBox> vertexBoxes(const Tin& tin) {
  std::vector<RtreeBox> boxes;
  boxes.reserve(tin.vertices.size());
  for (const TinVertex& v : tin.vertices) boxes.push_back(outwardBox({v.x, v.x, v.y, v.y}));
  return boxes;
}

std::vector<RtreeBox> triangleBoxes(const Tin& tin, std::size_t count, const TriangleAt& triangle) {
  std::vector<RtreeBox> boxes;
  boxes.reserve(count);
  addTriangleBoxes(tin.vertices, count, triangle, boxes);
  return boxes;
}

void addTriangleBoxes(const std::vector<TinVertex>& vertices, std::size_t count, const TriangleAt& triangle,
                      std::vector<RtreeBox>& boxes) {
  for (std::size_t i = 0; i < count; ++i) {
    const Triangle& t = triangle(i);
    Envelope e = Envelope::empty();
    for (int k = 0; k < 3; ++k) e.extend(vertices[t[k]].x, vertices[t[k]].y);
    boxes.push_back(outwardBox(e));
  }
}

}  // namespace tinlod
