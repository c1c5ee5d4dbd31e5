// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/tin.h"

#include <algorithm>
#include <utility>

#include "smallest_vertex_order.h"

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

namespace {

// Position along a Z-order curve over the TIN's bounding box, 16 bits an axis.
std::uint32_t zOrder(double x, double y, double x0, double y0, double sx, double sy) {
  auto spread = [](std::uint32_t v) {
    v = (v | (v << 8)) & 0x00FF00FFu;
    v = (v | (v << 4)) & 0x0F0F0F0Fu;
    v = (v | (v << 2)) & 0x33333333u;
    return (v | (v << 1)) & 0x55555555u;
  };
  const auto qx = static_cast<std::uint32_t>(std::clamp((x - x0) * sx, 0.0, 65535.0));
  const auto qy = static_cast<std::uint32_t>(std::clamp((y - y0) * sy, 0.0, 65535.0));
  return spread(qx) | (spread(qy) << 1);
}

}  // namespace

void orderSpatially(Tin& tin) {
  const std::size_t n = tin.vertices.size();
  if (n == 0) return;
  double x0 = tin.vertices[0].x, x1 = x0, y0 = tin.vertices[0].y, y1 = y0;
  for (const TinVertex& v : tin.vertices)
    x0 = std::min(x0, v.x), x1 = std::max(x1, v.x), y0 = std::min(y0, v.y), y1 = std::max(y1, v.y);
  const double sx = x1 > x0 ? 65535.0 / (x1 - x0) : 0, sy = y1 > y0 ? 65535.0 / (y1 - y0) : 0;
  std::vector<std::pair<std::uint32_t, VertexId>> order(n);
  for (std::size_t i = 0; i < n; ++i)
    order[i] = {zOrder(tin.vertices[i].x, tin.vertices[i].y, x0, y0, sx, sy), static_cast<VertexId>(i)};
  std::sort(order.begin(), order.end());  // equal positions keep their old order
  std::vector<VertexId> newId(n);
  std::vector<TinVertex> vertices(n);
  for (std::size_t i = 0; i < n; ++i) newId[order[i].second] = static_cast<VertexId>(i), vertices[i] = tin.vertices[order[i].second];
  tin.vertices.swap(vertices);
  for (Triangle& t : tin.triangles)
    for (VertexId& v : t) v = newId[v];
  // The triangles by their smallest vertex; neighbours follow.
  Compaction bySmallest;
  VertexTallies tallies;
  orderBySmallestVertex(tin.triangles.size(), n, [&](std::size_t t) {
    const Triangle& tri = tin.triangles[t];
    return static_cast<std::int32_t>(std::min({tri[0], tri[1], tri[2]}));
  }, bySmallest, tallies);
  const std::vector<std::int32_t>& position = bySmallest.newOf;
  std::vector<Triangle> ordered(tin.triangles.size());
  for (std::size_t t = 0; t < tin.triangles.size(); ++t) ordered[position[t]] = tin.triangles[t];
  tin.triangles.swap(ordered);
  if (tin.neighbours.size() != tin.triangles.size()) return tin.neighbours.clear();
  std::vector<std::array<std::int32_t, 3>> neighbours(tin.neighbours.size());
  for (std::size_t t = 0; t < position.size(); ++t)
    for (int k = 0; k < 3; ++k) neighbours[position[t]][k] = tin.neighbours[t][k] < 0 ? -1 : position[tin.neighbours[t][k]];
  tin.neighbours.swap(neighbours);
}

double totalArea(const Tin& tin) {
  double sum = 0;
  for (const Triangle& t : tin.triangles) sum += triangleArea(tin, t);
  return sum;
}

}  // namespace tinlod
