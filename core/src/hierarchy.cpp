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

void linkGroups(Hierarchy& h) {
  for (Group& g : h.groups) g.acceptBegin = g.acceptEnd = g.rejectBegin = g.rejectEnd = 0;
  for (const HierarchyTriangle& t : h.triangles) {
    if (t.replacedBy != kNoGroup) ++h.groups[t.replacedBy].acceptEnd;
    if (t.group != kNoGroup) ++h.groups[t.group].rejectEnd;
  }
  // Each group's range holds its accept triangles, then its reject ones.
  std::uint32_t next = 0;
  for (Group& g : h.groups) {
    const std::uint32_t accepts = g.acceptEnd, rejects = g.rejectEnd;
    g.acceptBegin = g.acceptEnd = next;
    g.rejectBegin = g.rejectEnd = next += accepts;
    next += rejects;
  }
  h.links.assign(next, 0);
  for (std::uint32_t t = 0; t < h.triangles.size(); ++t) {
    if (h.triangles[t].replacedBy != kNoGroup) h.links[h.groups[h.triangles[t].replacedBy].acceptEnd++] = t;
    if (h.triangles[t].group != kNoGroup) h.links[h.groups[h.triangles[t].group].rejectEnd++] = t;
  }
}

}  // namespace tinlod
