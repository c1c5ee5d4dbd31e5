// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/tin.h"

namespace tinlod {

double triangleArea(const Tin& tin, const Triangle& t) {
  const TinVertex& a = tin.vertices[t[0]];
  const TinVertex& b = tin.vertices[t[1]];
  const TinVertex& c = tin.vertices[t[2]];
  return 0.5 * ((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
}

std::vector<VertexId> dropUnusedVertices(Tin& tin) {
  constexpr VertexId kUnused = UINT32_MAX;
  std::vector<VertexId> newId(tin.vertices.size(), kUnused);
  for (const Triangle& t : tin.triangles)
    for (VertexId v : t) newId[v] = 0;
  std::vector<VertexId> oldId;
  std::vector<TinVertex> kept;
  for (std::size_t i = 0; i < tin.vertices.size(); ++i)
    if (newId[i] != kUnused) {
      newId[i] = static_cast<VertexId>(kept.size());
      oldId.push_back(static_cast<VertexId>(i));
      kept.push_back(tin.vertices[i]);
    }
  for (Triangle& t : tin.triangles)
    for (VertexId& v : t) v = newId[v];
  tin.vertices = std::move(kept);
  return oldId;
}

double totalArea(const Tin& tin) {
  double sum = 0;
  for (const Triangle& t : tin.triangles) sum += triangleArea(tin, t);
  return sum;
}

}  // namespace tinlod
