// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/lod_extraction.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include "tinlod/error.h"

namespace tinlod {

void LodOptions::validate() const {
  if (std::isnan(dropoff) && std::isnan(maxError) && !meetsRegion)
    throw Error("give a test: -dropoff (distance to the centre), -max_error (vertical error) or -region (polygons)");
  if (!std::isnan(dropoff) && !(dropoff >= 0))
    throw Error("-dropoff must be 0 or more metres per level (0: the coarsest level everywhere)");
  if (!std::isnan(dropoff) && centres.empty()) throw Error("-dropoff needs a centre of detail: -center X Y");
  if (!std::isnan(maxError) && !(maxError >= 0)) throw Error("-max_error must be 0 or more metres");
  if (!(errorGrowth >= 0) || !std::isfinite(errorGrowth)) throw Error("-error_growth must be 0 or more metres per metre");
  if (errorGrowth > 0 && std::isnan(maxError)) throw Error("-error_growth needs -max_error, the tolerance it grows from");
  if (errorGrowth > 0 && centres.empty()) throw Error("-error_growth needs a centre of detail: -center X Y");
}

namespace {

double nearestCentre(const LodOptions& o, const TinVertex& v) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& c : o.centres) best = std::min(best, std::hypot(v.x - c[0], v.y - c[1]));
  return best;
}

bool meetsRegion(const Hierarchy& h, const LodOptions& o, const Group& g) {
  const auto [begin, end] = h.reject(g);
  for (const std::uint32_t* r = begin; r != end; ++r) {
    std::array<std::array<double, 2>, 3> corners;
    for (int k = 0; k < 3; ++k) corners[k] = {h.base.vertices[h.triangles[*r].v[k]].x, h.base.vertices[h.triangles[*r].v[k]].y};
    if (o.meetsRegion(corners)) return true;
  }
  return false;
}

bool accepted(const Hierarchy& h, const LodOptions& o, const Group& g) {
  if (o.meetsRegion && meetsRegion(h, o, g)) return true;
  const TinVertex& v = h.base.vertices[g.vertex];
  const double d = o.centres.empty() ? 0 : nearestCentre(o, v);
  if (!std::isnan(o.dropoff) && d < g.level * o.dropoff) return true;
  return !std::isnan(o.maxError) && g.error > o.maxError + o.errorGrowth * d;
}

// The groups to refine: those the tests accept, and every coarser group whose accept
// triangles hold a reject triangle of one of them (finer levels first, so that the need
// climbs all the way up). Groups deleting one vertex (the tiles of a catalogue each have
// their own group for a vertex of the line they share, at the same level) go together,
// so that both tiles bring the vertex back and their sides of the line stay the same.
std::vector<bool> groupsToRefine(const Hierarchy& h, const LodOptions& o, LodVertices* vertices) {
  std::vector<std::uint32_t> order(h.groups.size());
  for (std::uint32_t g = 0; g < order.size(); ++g) order[g] = g;
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return h.groups[a].level < h.groups[b].level; });
  std::vector<bool> refine(h.groups.size(), false);
  std::vector<std::uint8_t> vertexBack(h.base.vertices.size(), 0);
  if (vertices && !vertices->forced.empty()) {
    if (vertices->forced.size() != vertexBack.size()) throw Error("internal error: forced vertices of another hierarchy");
    vertexBack = vertices->forced;
  }
  for (std::size_t begin = 0, end = 0; begin < order.size(); begin = end) {
    for (end = begin; end < order.size() && h.groups[order[end]].level == h.groups[order[begin]].level; ++end) {
      const std::uint32_t g = order[end];
      refine[g] = refine[g] || accepted(h, o, h.groups[g]);
      vertexBack[h.groups[g].vertex] |= refine[g];
    }
    for (std::size_t i = begin; i < end; ++i) {
      const std::uint32_t g = order[i];
      if (!vertexBack[h.groups[g].vertex]) continue;
      refine[g] = true;
      const auto [rb, re] = h.reject(h.groups[g]);
      for (const std::uint32_t* r = rb; r != re; ++r)
        if (h.triangles[*r].replacedBy != kNoGroup) refine[h.triangles[*r].replacedBy] = true;
    }
  }
  if (vertices) vertices->back = std::move(vertexBack);
  return refine;
}

}  // namespace

std::vector<std::uint32_t> extractLod(const Hierarchy& h, const LodOptions& options, const ProgressRange& progress,
                                      LodVertices* vertices) {
  options.validate();
  if (!h.linked()) throw Error("internal error: extracting from a hierarchy whose groups are not linked (linkGroups)");
  const std::vector<bool> refine = groupsToRefine(h, options, vertices);
  progress.report(0.3, "Extracting the TIN");
  // Coarser triangles first: a group is decided once every coarser one is.
  auto coarserFirst = [&](std::uint32_t a, std::uint32_t b) {
    return h.triangles[a].firstLevel != h.triangles[b].firstLevel ? h.triangles[a].firstLevel < h.triangles[b].firstLevel : a > b;
  };
  std::priority_queue<std::uint32_t, std::vector<std::uint32_t>, decltype(coarserFirst)> queue(coarserFirst);
  std::vector<std::uint8_t> queued(h.triangles.size(), 0);
  for (std::uint32_t t : h.levelTriangles(h.coarsest())) queue.push(t), queued[t] = 1;
  std::vector<std::uint32_t> out;
  while (!queue.empty()) {
    const std::uint32_t t = queue.top();
    queue.pop();
    if (!queued[t]) continue;  // replaced with the rest of its group
    queued[t] = 0;
    const std::int32_t g = h.triangles[t].group;
    if (g == kNoGroup || !refine[g]) {
      out.push_back(t);
      continue;
    }
    // Refining: the group's other reject triangles are queued too (the need climbed up to
    // every group that held them); all go, the accept triangles come in.
    const auto [rb, re] = h.reject(h.groups[g]);
    for (const std::uint32_t* r = rb; r != re; ++r) queued[*r] = 0;
    const auto [ab, ae] = h.accept(h.groups[g]);
    for (const std::uint32_t* a = ab; a != ae; ++a) queue.push(*a), queued[*a] = 1;
  }
  progress.report(1, "Extracting the TIN");
  return out;
}

}  // namespace tinlod
