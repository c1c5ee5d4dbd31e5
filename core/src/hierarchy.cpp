// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/hierarchy.h"

namespace tinlod {

std::vector<std::uint32_t> Hierarchy::levelTriangles(std::int32_t level) const {
  std::vector<std::uint32_t> out;
  for (std::uint32_t t = 0; t < triangles.size(); ++t)
    if (triangles[t].firstLevel <= level && level <= triangles[t].lastLevel) out.push_back(t);
  return out;
}

Tin Hierarchy::levelTin(std::int32_t level) const {
  Tin tin;
  tin.crsWkt = base.crsWkt;
  tin.crsName = base.crsName;
  std::vector<VertexId> newId(base.vertices.size(), UINT32_MAX);
  for (std::size_t v = 0; v < base.vertices.size(); ++v)
    if (vertexLevel[v] >= level) {
      newId[v] = static_cast<VertexId>(tin.vertices.size());
      tin.vertices.push_back(base.vertices[v]);
    }
  for (std::uint32_t t : levelTriangles(level)) {
    const Triangle& old = triangles[t].v;
    tin.triangles.push_back({newId[old[0]], newId[old[1]], newId[old[2]]});
  }
  return tin;
}

}  // namespace tinlod
