// SPDX-License-Identifier: GPL-3.0-or-later
#include "extracted_lod.h"

#include <utility>

namespace tinlod {

ExtractedLod extractedLod(const Hierarchy& h, const std::vector<std::uint32_t>& triangles, std::vector<VertexId>* kept) {
  ExtractedLod out;
  out.tin.crsWkt = h.base.crsWkt, out.tin.crsName = h.base.crsName;
  out.tin.vertices = h.base.vertices;
  for (std::uint32_t t : triangles) {
    out.tin.triangles.push_back(h.triangles[t].v);
    out.firstLevel.push_back(h.triangles[t].firstLevel);
    out.lastLevel.push_back(h.triangles[t].lastLevel);
  }
  std::vector<VertexId> ids = dropUnusedVertices(out.tin);
  for (VertexId v : ids) out.vertexLevel.push_back(h.vertexLevel[v]);
  out.levelZeroTriangles = h.levels.empty() ? 0 : h.levels[0].triangles;
  out.coarsest = h.coarsest();
  if (kept) *kept = std::move(ids);
  return out;
}

}  // namespace tinlod
