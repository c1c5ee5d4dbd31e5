// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/hierarchy_locator.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "box_grid.h"
#include "triangle_contains.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;

constexpr std::uint32_t kNone = UINT32_MAX;
constexpr std::uint32_t kOpenFan = 1u << 31;

// A triangle of the coarsest level with its corners: the start of every search.
struct TopTriangle {
  Point a, b, c;
  std::uint32_t id;
  std::uint32_t fan;  // the block of the group whose reject triangle it is; kNone at level 0
};

Box boxOf(const TopTriangle& t) {
  return {std::min({t.a.x(), t.b.x(), t.c.x()}), std::min({t.a.y(), t.b.y(), t.c.y()}),
          std::max({t.a.x(), t.b.x(), t.c.x()}), std::max({t.a.y(), t.b.y(), t.c.y()})};
}

// Buckets over the coarsest level, in ascending triangle id, so that the start of a search
// costs a few containment tests whatever the size of the TIN.
BoxGrid makeGrid(const std::vector<TopTriangle>& top) {
  std::vector<Box> boxes;
  boxes.reserve(top.size());
  for (const TopTriangle& t : top) boxes.push_back(boxOf(t));
  return BoxGrid(boxes);
}

std::vector<Point> pointsOf(const Tin& base) {
  std::vector<Point> points;
  points.reserve(base.vertices.size());
  for (const TinVertex& v : base.vertices) points.emplace_back(v.x, v.y);
  return points;
}

// Where the block of the group that made triangle t begins; kNone for level 0.
std::uint32_t fanOf(const Hierarchy& h, const std::vector<std::uint32_t>& fanStart, std::uint32_t t) {
  const std::int32_t g = h.triangles[t].group;
  return g == kNoGroup ? kNone : fanStart[static_cast<std::size_t>(g)];
}

// levelTriangles() is in ascending id, so the buckets are too: the first containing
// triangle of a bucket is the lowest id.
std::vector<TopTriangle> topTriangles(const Hierarchy& h, const std::vector<Point>& points,
                                      const std::vector<std::uint32_t>& fanStart) {
  std::vector<TopTriangle> top;
  if (h.coarsest() < 0) return top;
  for (std::uint32_t t : h.levelTriangles(h.coarsest())) {
    const Triangle& v = h.triangles[t].v;
    top.push_back({points[v[0]], points[v[1]], points[v[2]], t, fanOf(h, fanStart, t)});
  }
  return top;
}

// One step of the descent reads one group's star: its deleted vertex and the ring of
// its accept triangles, stored together so that the step reads a few consecutive cache
// lines rather than a triangle, three vertices and a link per candidate (the hierarchy's
// own arrays are far larger than the caches: the search is bound by memory latency).
// A block is a head {vertex, k, level}, then k ring entries {ring vertex, accept
// triangle, the block of the group that made that triangle}: entry i and the next
// (cyclically) span accept triangle i with the head's vertex. An outline vertex's fan is
// open: one more entry holds the last ring vertex, and the head's level has kOpenFan set.
// Linking blocks directly, not through group ids, spares a dependent cache miss per level.
struct FanEntry {
  Point p;
  std::uint32_t a = 0;  // head: the ring's size; ring entry: the accept triangle
  std::uint32_t b = 0;  // head: the group's level; ring entry: the next block, kNone at level 0
};

// Blocks in the order of their vertex along a Z-order curve: the groups a search meets
// are all near its point, so they end up nearer in memory (fewer page and TLB misses)
// than in the order the levels were made.
std::vector<std::uint32_t> spatialOrder(const Hierarchy& h, const std::vector<Point>& points) {
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (const Group& g : h.groups) {
    const Point& p = points[g.vertex];
    x0 = std::min(x0, p.x()), y0 = std::min(y0, p.y()), x1 = std::max(x1, p.x()), y1 = std::max(y1, p.y());
  }
  const auto cell = [](double v, double lo, double hi) {
    return hi > lo ? static_cast<std::uint64_t>(std::min(65535.0, (v - lo) / (hi - lo) * 65536)) : 0;
  };
  const auto spread = [](std::uint64_t v) {  // bit i goes to bit 2i
    v = (v | (v << 8)) & 0x00FF00FFu, v = (v | (v << 4)) & 0x0F0F0F0Fu;
    v = (v | (v << 2)) & 0x33333333u, v = (v | (v << 1)) & 0x55555555u;
    return v;
  };
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
  keyed.reserve(h.groups.size());
  for (std::uint32_t g = 0; g < h.groups.size(); ++g) {
    const Point& p = points[h.groups[g].vertex];
    keyed.push_back({spread(cell(p.x(), x0, x1)) | spread(cell(p.y(), y0, y1)) << 1, g});
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> order;
  order.reserve(keyed.size());
  for (const auto& k : keyed) order.push_back(k.second);
  return order;
}

std::string groupName(const Hierarchy& h, std::size_t g) {
  return "group " + std::to_string(g) + " (vertex " + std::to_string(h.groups[g].vertex) + ")";
}

// The accept triangles turned to start at the deleted vertex, in counter-clockwise order
// around it: each one's last corner is the next one's second. Checked rather than
// assumed, so that an inconsistent file fails here and not in a search.
std::vector<std::uint32_t> ringOrder(const Hierarchy& h, std::size_t g, std::vector<std::array<VertexId, 3>>& turned) {
  const VertexId v = h.groups[g].vertex;
  const auto [begin, end] = h.accept(h.groups[g]);
  turned.clear();
  for (const std::uint32_t* t = begin; t != end; ++t) {
    Triangle c = h.triangles[*t].v;
    const auto at = std::find(c.begin(), c.end(), v);
    if (at == c.end())
      throw Error("the hierarchy is inconsistent: an accept triangle of " + groupName(h, g) + " lacks its vertex");
    std::rotate(c.begin(), at, c.end());
    turned.push_back(c);
  }
  // An outline vertex's fan is open: it starts at the triangle no other one precedes.
  std::size_t first = 0;
  for (std::size_t i = 0; i < turned.size(); ++i)
    if (std::none_of(turned.begin(), turned.end(), [&](const auto& c) { return c[2] == turned[i][1]; })) first = i;
  std::vector<std::uint32_t> order;
  for (std::size_t i = first; order.size() < turned.size();) {
    order.push_back(static_cast<std::uint32_t>(i));
    const auto next = std::find_if(turned.begin(), turned.end(), [&](const auto& c) { return c[1] == turned[i][2]; });
    if (next == turned.end()) break;
    i = static_cast<std::size_t>(next - turned.begin());
    if (i == first) break;
  }
  const bool closed = !turned.empty() && turned[order.back()][2] == turned[order.front()][1];
  const std::size_t rejects = static_cast<std::size_t>(h.groups[g].rejectEnd - h.groups[g].rejectBegin);
  if (order.size() != turned.size() || turned.empty() || rejects + (closed ? 2 : 1) != turned.size())
    throw Error("the hierarchy is inconsistent: the accept triangles of " + groupName(h, g) + " are not a fan");
  return order;
}

bool openFan(const Group& g) { return g.acceptEnd - g.acceptBegin == g.rejectEnd - g.rejectBegin + 1; }

// An accept triangle must be older than the group that replaced it: each step of a
// search then goes down a level, and a corrupt file cannot send it round in circles.
void checkOlder(const Hierarchy& h, std::size_t g, std::uint32_t accept) {
  const std::int32_t maker = h.triangles[accept].group;
  if (maker != kNoGroup && h.groups[static_cast<std::size_t>(maker)].level >= h.groups[g].level)
    throw Error("the hierarchy is inconsistent: an accept triangle of " + groupName(h, g) +
                " is not from a finer level");
}

void appendFan(const Hierarchy& h, const std::vector<Point>& points, const std::vector<std::uint32_t>& fanStart,
               std::size_t g, std::vector<FanEntry>& fans, std::vector<std::array<VertexId, 3>>& turned) {
  const std::vector<std::uint32_t> order = ringOrder(h, g, turned);
  const Group& group = h.groups[g];
  const bool open = openFan(group);
  const auto level = static_cast<std::uint32_t>(group.level) | (open ? kOpenFan : 0);
  fans.push_back({points[group.vertex], static_cast<std::uint32_t>(order.size()), level});
  const std::uint32_t* accept = h.accept(group).first;
  for (std::uint32_t i : order) {
    checkOlder(h, g, accept[i]);
    fans.push_back({points[turned[i][1]], accept[i], fanOf(h, fanStart, accept[i])});
  }
  if (open) fans.push_back({points[turned[order.back()][2]], kNone, kNone});
}

// Two passes: where each block begins (in spatial order), then the blocks, whose links
// need every start.
std::vector<FanEntry> makeFans(const Hierarchy& h, const std::vector<Point>& points,
                               std::vector<std::uint32_t>& fanStart) {
  const std::vector<std::uint32_t> order = spatialOrder(h, points);
  fanStart.assign(h.groups.size(), 0);
  std::size_t size = 0;
  for (std::uint32_t g : order) {
    const std::size_t block = 2 + (h.groups[g].acceptEnd - h.groups[g].acceptBegin);
    if (size + block >= kNone)
      throw Error("the hierarchy is too large to locate points in (over 4 billion accept triangles)");
    fanStart[g] = static_cast<std::uint32_t>(size);
    size += block - !openFan(h.groups[g]);
  }
  std::vector<FanEntry> fans;
  fans.reserve(size);
  std::vector<std::array<VertexId, 3>> turned;
  for (std::uint32_t g : order) appendFan(h, points, fanStart, g, fans, turned);
  return fans;
}

constexpr double kDiagonal = 0.70710678118654752;
constexpr double kDirections[8][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1},
                                      {kDiagonal, kDiagonal}, {-kDiagonal, kDiagonal}, {-kDiagonal, -kDiagonal}, {kDiagonal, -kDiagonal}};

// A DEM cell's size in the TIN's CRS, as the simplifier takes it (the square root of a
// cell's area): the median over some of the first triangles of their area over their area
// in the DEM's grid (where the sampler placed the vertices).
double cellSize(const Hierarchy& h) {
  std::vector<double> ratios;
  for (std::size_t t = 0; t < h.triangles.size() && ratios.size() < 257; ++t) {
    const Triangle& v = h.triangles[t].v;
    const TinVertex &a = h.base.vertices[v[0]], &b = h.base.vertices[v[1]], &c = h.base.vertices[v[2]];
    const auto gx = [](const TinVertex& p) { return double(p.col) + p.dcol; };
    const auto gy = [](const TinVertex& p) { return double(p.row) + p.drow; };
    const double grid = std::fabs((gx(b) - gx(a)) * (gy(c) - gy(a)) - (gy(b) - gy(a)) * (gx(c) - gx(a)));
    const double area = std::fabs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    if (grid > 0.25 && area > 0) ratios.push_back(area / grid);
  }
  if (ratios.empty()) return 0;
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  return std::sqrt(ratios[ratios.size() / 2]);
}

}  // namespace

struct HierarchyLocator::Impl {
  const Hierarchy& h;
  std::vector<TopTriangle> top;
  BoxGrid grid;
  std::vector<FanEntry> fans;  // every group's block
  std::vector<std::uint32_t> cuts;  // the blocks of outline vertices, whose ground was given up
  BoxGrid cutGrid;
  // How far off the TIN a point may lie and still take its nearest triangle: the centres
  // of the edge cells of a DEM in degrees lie on curves in the TIN's CRS, a fraction of a
  // millimetre outside the straight edges between its vertices at level 0 (and up to a few
  // per cent of a cell at coarse levels, whose edge vertices are far apart).
  double reach = 0;
  std::array<std::int32_t, 2> rows{0, 0}, cols{0, 0};  // the first and last of the TIN's cells

  explicit Impl(const Hierarchy& hierarchy) : h(hierarchy), reach(kRasterEdgeReach * cellSize(hierarchy)) {
    if (!h.base.vertices.empty()) {
      rows = {h.base.vertices[0].row, h.base.vertices[0].row}, cols = {h.base.vertices[0].col, h.base.vertices[0].col};
      for (const TinVertex& v : h.base.vertices) {
        rows = {std::min(rows[0], std::int32_t(v.row)), std::max(rows[1], std::int32_t(v.row))};
        cols = {std::min(cols[0], std::int32_t(v.col)), std::max(cols[1], std::int32_t(v.col))};
      }
    }
    if (!h.linked()) throw Error("internal error: locating in a hierarchy whose groups are not linked (linkGroups)");
    const std::vector<Point> points = pointsOf(h.base);
    std::vector<std::uint32_t> fanStart;  // by group: where its block begins in `fans`
    fans = makeFans(h, points, fanStart);
    top = topTriangles(h, points, fanStart);
    grid = makeGrid(top);
    std::vector<Box> boxes;
    for (std::size_t g = 0; g < h.groups.size(); ++g) {
      if (!openFan(h.groups[g])) continue;
      const FanEntry* head = &fans[fanStart[g]];
      const Point &a = head->p, &b = head[1].p, &c = head[head->a + 1].p;
      cuts.push_back(fanStart[g]);
      boxes.push_back({std::min({a.x(), b.x(), c.x()}), std::min({a.y(), b.y(), c.y()}), std::max({a.x(), b.x(), c.x()}),
                       std::max({a.y(), b.y(), c.y()})});
    }
    cutGrid = BoxGrid(boxes);
  }

  // The first triangle of p's bucket that holds it, or null (off the TIN, or in a hole).
  const TopTriangle* start(const Point& p) const {
    const auto [first, last] = grid.at(p.x(), p.y());
    for (const std::uint32_t* i = first; i != last; ++i) {
      const TopTriangle& t = top[*i];
      if (triangleContains(t.a, t.b, t.c, p)) return &t;
    }
    return nullptr;
  }

  // Ground the outline gave up: where an outline vertex went, the triangle between it and
  // its two outline neighbours is covered by its accept triangles and by nothing coarser
  // (unless a later straightening of the outline covered it again). Each such triangle of
  // a group coarser than `level` that holds p is a start one level finer than its group:
  // the triangle of `level` the first of them reaches, or kNone.
  std::uint32_t fromGivenUp(const Point& p, int level) const {
    const auto [first, last] = cutGrid.at(p.x(), p.y());
    for (const std::uint32_t* i = first; i != last; ++i) {
      const FanEntry* head = &fans[cuts[*i]];
      const std::uint32_t k = head->a;
      if (levelOf(*head) <= level) continue;
      if (!triangleContains(head->p, head[1].p, head[k + 1].p, p) && !triangleContains(head->p, head[k + 1].p, head[1].p, p))
        continue;
      if (const FanEntry* e = finer(head, p)) {
        const std::uint32_t t = descend(e->a, e->b, p, level);
        if (t != kNone) return t;
      }
    }
    return kNone;
  }

  // The accept triangle of a block that holds p, first in ring order: a ring entry; null
  // when none does (a point an outline vertex's deletion newly covered, at a raster edge).
  // The test is closed and exact.
  const FanEntry* finer(const FanEntry* head, const Point& p) const {
    const std::uint32_t k = head->a;
    const bool open = (head->b & kOpenFan) != 0;
    for (std::uint32_t i = 1; i <= k; ++i)
      if (triangleContains(head->p, head[i].p, head[i == k && !open ? 1 : i + 1].p, p)) return &head[i];
    if (!open)
      throw Error("internal error: the hierarchy is inconsistent: a point of the reject triangles of the vertex at (" +
                  std::to_string(head->p.x()) + ", " + std::to_string(head->p.y()) +
                  ") is in none of its accept triangles");
    return nullptr;
  }

  static int levelOf(const FanEntry& head) { return static_cast<int>(head.b & ~kOpenFan); }

  // A triangle newer than `level` was made by deleting its group's vertex; the star that
  // vertex had one level finer covers the same polygon (or, at the outline, the same and
  // what it gave up), so one of its accept triangles holds p. Each step goes down at
  // least one level. kNone when p is not on the TIN at `level`.
  std::uint32_t descend(std::uint32_t t, std::uint32_t fan, const Point& p, int level) const {
    while (fan != kNone && levelOf(fans[fan]) > level) {
      const FanEntry* e = finer(&fans[fan], p);
      if (!e) return kNone;
      t = e->a;
      fan = e->b;
    }
    return t;
  }

  // Whether p lies within reach of an edge of triangle t between two vertices on the
  // raster's edge: the first or last row or column of the TIN's cells (a tile's, for a tile).
  bool beyondRasterEdge(std::uint32_t t, const Point& p) const {
    const Triangle& v = h.triangles[t].v;
    for (int k = 0; k < 3; ++k) {
      const TinVertex &a = h.base.vertices[v[k]], &b = h.base.vertices[v[(k + 1) % 3]];
      // Both ends on the raster's edge: along one of its lines, or across a corner.
      const auto onEdge = [&](const TinVertex& u) {
        return u.row == rows[0] || u.row == rows[1] || u.col == cols[0] || u.col == cols[1];
      };
      if (!onEdge(a) || !onEdge(b)) continue;
      const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
      const double s = len2 > 0 ? std::clamp(((p.x() - a.x) * dx + (p.y() - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
      if (std::hypot(p.x() - a.x - s * dx, p.y() - a.y - s * dy) <= reach) return true;
    }
    return false;
  }

  std::uint32_t triangleAt(const Point& p, int level) const {
    std::uint32_t t = kNone;
    if (const TopTriangle* top = start(p)) t = descend(top->id, top->fan, p, level);
    if (t == kNone) t = fromGivenUp(p, level);  // on ground the outline gave up at a coarser level
    return t;
  }

  // Linear in the triangle, from the areas opposite each vertex. Normalising each by
  // their sum, rather than by the triangle's area, gives a vertex exactly its own
  // height: the other two areas are then exactly zero and its weight exactly one.
  double height(std::uint32_t t, const Point& p) const {
    const Triangle& v = h.triangles[t].v;
    const TinVertex* c[3] = {&h.base.vertices[v[0]], &h.base.vertices[v[1]], &h.base.vertices[v[2]]};
    double w[3], sum = 0, z = 0;
    for (int k = 0; k < 3; ++k) {
      const TinVertex &b = *c[(k + 1) % 3], &d = *c[(k + 2) % 3];
      w[k] = (b.x - p.x()) * (d.y - p.y()) - (b.y - p.y()) * (d.x - p.x());
      sum += w[k];
    }
    for (int k = 0; k < 3; ++k) z += w[k] / sum * c[k]->z;
    return z;
  }
};

HierarchyLocator::HierarchyLocator(const Hierarchy& h) : impl_(std::make_unique<const Impl>(h)) {}
HierarchyLocator::~HierarchyLocator() = default;
HierarchyLocator::HierarchyLocator(HierarchyLocator&&) noexcept = default;
HierarchyLocator& HierarchyLocator::operator=(HierarchyLocator&&) noexcept = default;

double HierarchyLocator::reach() const { return impl_->reach; }

LocatedPoint HierarchyLocator::locate(double x, double y, int level) const {
  const std::int32_t coarsest = impl_->h.coarsest();
  if (level < 0 || level > coarsest)
    throw Error("cannot locate a point at level " + std::to_string(level) + ": the hierarchy has levels 0 to " +
                std::to_string(coarsest));
  const Point p(x, y);
  std::uint32_t t = impl_->triangleAt(p, level);
  // Just beyond the raster's edge: the triangle a little way towards it, nearest first, its
  // plane's height at p. Not beside a hole: the nodata cells there stay off the TIN.
  // From a 4096th of the reach: the triangles along a curved edge can be slivers centimetres thin.
  for (double d = impl_->reach / 4096; t == kNone && d <= impl_->reach && d > 0; d *= 8)
    for (int k = 0; k < 8 && t == kNone; ++k) {
      const std::uint32_t near = impl_->triangleAt(Point(x + d * kDirections[k][0], y + d * kDirections[k][1]), level);
      if (near != kNone && impl_->beyondRasterEdge(near, p)) t = near;
    }
  if (t == kNone) return {};  // off the TIN or in a hole at that level
  return {static_cast<std::int64_t>(t), impl_->height(t, p)};
}

}  // namespace tinlod
