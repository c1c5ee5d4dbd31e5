// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh_checks.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <map>
#include <cmath>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

#include "tinlod/crs_transform.h"

namespace tinlod::test {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P2 = K::Point_2;

P2 point(const Tin& tin, VertexId v) { return P2(tin.vertices[v].x, tin.vertices[v].y); }

std::uint64_t key(VertexId a, VertexId b) { return (std::uint64_t(a) << 32) | b; }

struct UnionFind {
  std::vector<std::size_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  std::size_t find(std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::size_t a, std::size_t b) { parent[find(a)] = find(b); }
  std::size_t sets() {
    std::size_t n = 0;
    for (std::size_t i = 0; i < parent.size(); ++i) n += find(i) == i;
    return n;
  }
};

// A uniform grid of vertex ids for range queries.
class VertexGrid {
 public:
  explicit VertexGrid(const Tin& tin) : tin_(tin) {
    minX_ = minY_ = INFINITY;
    double maxX = -INFINITY, maxY = -INFINITY;
    for (const TinVertex& v : tin.vertices) {
      minX_ = std::min(minX_, v.x), minY_ = std::min(minY_, v.y);
      maxX = std::max(maxX, v.x), maxY = std::max(maxY, v.y);
    }
    const double cells = std::max(1.0, std::sqrt(double(tin.vertices.size())));
    size_ = std::max((maxX - minX_), (maxY - minY_)) / cells + 1e-9;
    nx_ = int((maxX - minX_) / size_) + 1;
    ny_ = int((maxY - minY_) / size_) + 1;
    buckets_.resize(std::size_t(nx_) * ny_);
    for (VertexId i = 0; i < tin.vertices.size(); ++i) buckets_[bucket(tin.vertices[i].x, tin.vertices[i].y)].push_back(i);
  }
  template <typename F>
  void forEachIn(double x0, double y0, double x1, double y1, F&& f) const {
    const int i0 = clampX(x0), i1 = clampX(x1), j0 = clampY(y0), j1 = clampY(y1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
        for (VertexId v : buckets_[std::size_t(j) * nx_ + i]) f(v);
  }

 private:
  int clampX(double x) const { return std::clamp(int(std::floor((x - minX_) / size_)), 0, nx_ - 1); }
  int clampY(double y) const { return std::clamp(int(std::floor((y - minY_) / size_)), 0, ny_ - 1); }
  std::size_t bucket(double x, double y) const { return std::size_t(clampY(y)) * nx_ + clampX(x); }
  const Tin& tin_;
  double minX_, minY_, size_;
  int nx_, ny_;
  std::vector<std::vector<VertexId>> buckets_;
};

std::size_t countBoundaryLoops(const std::unordered_map<std::size_t, std::size_t>& next, std::string& problem) {
  std::unordered_set<std::size_t> seen;
  std::size_t loops = 0;
  for (const auto& [start, ignored] : next) {
    if (seen.count(start)) continue;
    ++loops;
    std::size_t at = start;
    while (!seen.count(at)) {
      seen.insert(at);
      auto it = next.find(at);
      if (it == next.end()) {
        problem = "a boundary that does not close";
        return loops;
      }
      at = it->second;
    }
  }
  return loops;
}

}  // namespace

Topology analyseTopology(const Tin& tin) {
  Topology t;
  t.faces = tin.triangles.size();
  std::unordered_map<std::uint64_t, std::size_t> halfEdges;  // directed edge -> corner index 3*tri+k
  halfEdges.reserve(tin.triangles.size() * 3);
  for (std::size_t f = 0; f < tin.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const VertexId a = tin.triangles[f][k], b = tin.triangles[f][(k + 1) % 3];
      if (!halfEdges.emplace(key(a, b), 3 * f + k).second) t.problem = "an edge used twice in one direction";
    }
  UnionFind corners(tin.triangles.size() * 3), faces(tin.triangles.size());
  std::unordered_map<std::size_t, std::size_t> boundaryNext;  // start corner's fan -> end corner's fan, filled below
  std::vector<std::pair<std::size_t, std::size_t>> boundary;  // (corner at a, corner at b) of boundary edges
  for (const auto& [k, corner] : halfEdges) {
    const VertexId a = VertexId(k >> 32), b = VertexId(k & 0xFFFFFFFF);
    const std::size_t f = corner / 3, i = corner % 3;
    const std::size_t cornerB = 3 * f + (i + 1) % 3;
    auto twin = halfEdges.find(key(b, a));
    if (twin == halfEdges.end()) {
      boundary.emplace_back(corner, cornerB);
      t.perimeter += std::hypot(tin.vertices[a].x - tin.vertices[b].x, tin.vertices[a].y - tin.vertices[b].y);
      ++t.edges;
      continue;
    }
    if (a < b) ++t.edges;
    const std::size_t g = twin->second / 3, j = twin->second % 3;  // twin is b -> a: corner j at b
    corners.unite(cornerB, twin->second);
    corners.unite(corner, 3 * g + (j + 1) % 3);
    faces.unite(f, g);
  }
  t.fans = corners.sets();
  t.components = faces.sets();
  for (const auto& [ca, cb] : boundary)
    if (!boundaryNext.emplace(corners.find(ca), corners.find(cb)).second) t.problem = "a vertex fan with two boundaries";
  if (t.problem.empty()) t.boundaryLoops = countBoundaryLoops(boundaryNext, t.problem);
  std::vector<bool> used(tin.vertices.size(), false);
  for (const Triangle& tri : tin.triangles)
    for (VertexId v : tri) used[v] = true;
  t.unusedVertices = std::count(used.begin(), used.end(), false);
  return t;
}

std::size_t clockwiseTriangles(const Tin& tin) {
  std::size_t n = 0;
  for (const Triangle& t : tin.triangles)
    n += CGAL::orientation(point(tin, t[0]), point(tin, t[1]), point(tin, t[2])) != CGAL::LEFT_TURN;
  return n;
}

std::size_t delaunayViolations(const Tin& tin) {
  const VertexGrid grid(tin);
  std::size_t violations = 0;
  for (const Triangle& t : tin.triangles) {
    const P2 p = point(tin, t[0]), q = point(tin, t[1]), r = point(tin, t[2]);
    const P2 c = CGAL::circumcenter(p, q, r);
    const double radius = std::sqrt(CGAL::squared_distance(c, p)) * (1 + 1e-9) + 1e-6;
    grid.forEachIn(c.x() - radius, c.y() - radius, c.x() + radius, c.y() + radius, [&](VertexId v) {
      if (v == t[0] || v == t[1] || v == t[2]) return;
      violations += CGAL::side_of_oriented_circle(p, q, r, point(tin, v)) == CGAL::ON_POSITIVE_SIDE;
    });
  }
  return violations;
}

std::size_t localDelaunayViolations(const Tin& tin) {
  std::map<std::pair<VertexId, VertexId>, VertexId> opposite;  // directed edge -> third corner
  for (const Triangle& t : tin.triangles)
    for (int k = 0; k < 3; ++k) opposite[{t[k], t[(k + 1) % 3]}] = t[(k + 2) % 3];
  std::size_t violations = 0;
  for (const auto& [edge, c] : opposite) {
    const auto twin = opposite.find({edge.second, edge.first});
    if (twin == opposite.end()) continue;
    violations += CGAL::side_of_oriented_circle(point(tin, edge.first), point(tin, edge.second), point(tin, c),
                                                point(tin, twin->second)) == CGAL::ON_POSITIVE_SIDE;
  }
  return violations;
}

std::size_t verticesInsideTriangles(const Tin& tin) {
  const VertexGrid grid(tin);
  std::size_t inside = 0;
  for (const Triangle& t : tin.triangles) {
    const P2 p = point(tin, t[0]), q = point(tin, t[1]), r = point(tin, t[2]);
    const double x0 = std::min({p.x(), q.x(), r.x()}), x1 = std::max({p.x(), q.x(), r.x()});
    const double y0 = std::min({p.y(), q.y(), r.y()}), y1 = std::max({p.y(), q.y(), r.y()});
    grid.forEachIn(x0, y0, x1, y1, [&](VertexId v) {
      if (v == t[0] || v == t[1] || v == t[2]) return;
      const P2 s = point(tin, v);
      inside += CGAL::orientation(p, q, s) == CGAL::LEFT_TURN && CGAL::orientation(q, r, s) == CGAL::LEFT_TURN &&
                CGAL::orientation(r, p, s) == CGAL::LEFT_TURN;
    });
  }
  return inside;
}

std::size_t trianglesOverNodata(const Dem& dem, const Tin& tin) {
  std::size_t n = 0;
  for (const Triangle& t : tin.triangles) {
    P2 g[3];
    int r0 = INT32_MAX, r1 = INT32_MIN, c0 = INT32_MAX, c1 = INT32_MIN;
    for (int k = 0; k < 3; ++k) {
      const TinVertex& v = tin.vertices[t[k]];
      g[k] = P2(v.col, v.row);
      r0 = std::min(r0, v.row), r1 = std::max(r1, v.row), c0 = std::min(c0, v.col), c1 = std::max(c1, v.col);
    }
    const CGAL::Orientation o = CGAL::orientation(g[0], g[1], g[2]);
    bool over = false;
    for (int r = r0; r <= r1 && !over; ++r)
      for (int c = c0; c <= c1 && !over; ++c) {
        if (dem.valid(r, c)) continue;
        const P2 q(c, r);
        if (o == CGAL::COLLINEAR) {
          over = CGAL::collinear(g[0], g[1], q) && CGAL::collinear(g[1], g[2], q);
        } else {
          const K::Triangle_2 tri = o == CGAL::LEFT_TURN ? K::Triangle_2(g[0], g[1], g[2]) : K::Triangle_2(g[0], g[2], g[1]);
          over = tri.bounded_side(q) != CGAL::ON_UNBOUNDED_SIDE;
        }
      }
    n += over;
  }
  return n;
}

std::size_t verticesOnNodata(const Dem& dem, const Tin& tin) {
  return std::count_if(tin.vertices.begin(), tin.vertices.end(),
                       [&](const TinVertex& v) { return !dem.valid(v.row, v.col); });
}

GridCoverage gridCoverage(const Dem& dem, const Tin& tin) {
  GridCoverage g;
  for (const Triangle& t : tin.triangles) {
    const TinVertex &a = tin.vertices[t[0]], &b = tin.vertices[t[1]], &c = tin.vertices[t[2]];
    const long twice = long(b.col - a.col) * (c.row - a.row) - long(c.col - a.col) * (b.row - a.row);
    g.tinCells += std::labs(twice) / 2.0;
  }
  for (int r = 0; r + 1 < dem.height; ++r)
    for (int c = 0; c + 1 < dem.width; ++c) {
      const int n = dem.valid(r, c) + dem.valid(r, c + 1) + dem.valid(r + 1, c) + dem.valid(r + 1, c + 1);
      g.extentCells += n == 4 ? 1.0 : n == 3 ? 0.5 : 0.0;
      g.boundaryBlocks += n == 2 || n == 3;
    }
  return g;
}

double unjitteredArea(const Dem& dem, const Tin& tin, const std::string& sourceSrs) {
  const CrsTransform transform = CrsTransform::forDem(dem, sourceSrs, "", ProgressRange(Feedback{}, 0, 1));
  std::vector<double> x(tin.vertices.size()), y(tin.vertices.size());
  for (std::size_t i = 0; i < tin.vertices.size(); ++i) {
    x[i] = dem.centreX(tin.vertices[i].col);
    y[i] = dem.centreY(tin.vertices[i].row);
  }
  transform.apply(x, y);
  double area = 0;
  for (const Triangle& t : tin.triangles)
    area += 0.5 * ((x[t[1]] - x[t[0]]) * (y[t[2]] - y[t[0]]) - (x[t[2]] - x[t[0]]) * (y[t[1]] - y[t[0]]));
  return area;
}

std::vector<double> cellDistances(const Dem& dem, const Hierarchy& h, std::int32_t level,
                                  const std::function<std::array<double, 2>(const TinVertex&)>& gridPlace) {
  std::vector<double> out(dem.z.size(), NAN);
  for (std::uint32_t id : h.levelTriangles(level)) {
    const Triangle& t = h.triangles[id].v;
    double c[3], r[3], z[3];
    for (int k = 0; k < 3; ++k) {
      const TinVertex& v = h.base.vertices[t[k]];
      const std::array<double, 2> at = gridPlace(v);
      c[k] = at[0], r[k] = at[1], z[k] = v.z;
    }
    const double d = (c[1] - c[0]) * (r[2] - r[0]) - (c[2] - c[0]) * (r[1] - r[0]);
    if (d == 0) continue;
    // The footprint's box, a little wider: a place from x and y may miss a whole number by a rounding.
    const int r0 = std::max(0, int(std::ceil(std::min({r[0], r[1], r[2]}) - 1e-9)));
    const int r1 = std::min(dem.height - 1, int(std::floor(std::max({r[0], r[1], r[2]}) + 1e-9)));
    const int c0 = std::max(0, int(std::ceil(std::min({c[0], c[1], c[2]}) - 1e-9)));
    const int c1 = std::min(dem.width - 1, int(std::floor(std::max({c[0], c[1], c[2]}) + 1e-9)));
    for (int row = r0; row <= r1; ++row)
      for (int col = c0; col <= c1; ++col) {
        const std::size_t cell = std::size_t(row) * dem.width + col;
        if (!std::isnan(out[cell]) || !dem.valid(row, col)) continue;
        const double wb = ((col - c[0]) * (r[2] - r[0]) - (c[2] - c[0]) * (row - r[0])) / d;
        const double wc = ((c[1] - c[0]) * (row - r[0]) - (col - c[0]) * (r[1] - r[0])) / d;
        if (wb < -1e-9 || wc < -1e-9 || wb + wc > 1 + 1e-9) continue;
        out[cell] = std::fabs(dem.at(row, col) - (z[0] + wb * (z[1] - z[0]) + wc * (z[2] - z[0])));
      }
  }
  return out;
}

}  // namespace tinlod::test
