// SPDX-License-Identifier: GPL-3.0-or-later
#include "tin_layers.h"

namespace tinlod {

std::vector<FieldSpec> vertexFields() {
  return {{"id"}, {"row"}, {"col"}, {"outline", OFTInteger, OFSTBoolean}};
}

std::vector<FieldSpec> triangleFields() { return {{"id"}, {"v0"}, {"v1"}, {"v2"}}; }

void writeVertices(const Tin& tin, OGRLayer& layer, const MoreFields& more, const ProgressRange& progress) {
  OGRFeature feature(layer.GetLayerDefn());
  for (std::size_t i = 0; i < tin.vertices.size(); ++i) {
    const TinVertex& v = tin.vertices[i];
    feature.SetFID(static_cast<GIntBig>(i) + 1);
    feature.SetField(0, static_cast<int>(i) + 1);
    feature.SetField(1, v.row);
    feature.SetField(2, v.col);
    feature.SetField(3, v.outline ? 1 : 0);
    if (more) more(feature, i);
    feature.SetGeometryDirectly(new OGRPoint(v.x, v.y, v.z));
    writeFeature(layer, feature);
    if ((i & 0x3FFF) == 0) progress.report(double(i) / tin.vertices.size(), "Writing vertices");
  }
}

void writeTriangles(const Tin& tin, const std::vector<Triangle>& triangles, OGRLayer& layer, const MoreFields& more,
                    const ProgressRange& progress) {
  OGRFeature feature(layer.GetLayerDefn());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const Triangle& t = triangles[i];
    auto* ring = new OGRLinearRing();
    ring->setNumPoints(4);
    for (int k = 0; k < 4; ++k) {
      const TinVertex& v = tin.vertices[t[k % 3]];
      ring->setPoint(k, v.x, v.y, v.z);
    }
    auto* polygon = new OGRPolygon();
    polygon->addRingDirectly(ring);
    feature.SetFID(static_cast<GIntBig>(i) + 1);
    feature.SetField(0, static_cast<int>(i) + 1);
    for (int k = 0; k < 3; ++k) feature.SetField(k + 1, static_cast<int>(t[k]) + 1);
    if (more) more(feature, i);
    feature.SetGeometryDirectly(polygon);
    writeFeature(layer, feature);
    if ((i & 0x3FFF) == 0) progress.report(double(i) / triangles.size(), "Writing triangles");
  }
}

}  // namespace tinlod
