// SPDX-License-Identifier: GPL-3.0-or-later
// The fill of an outline vertex's star: its polygon is not star-shaped around the vertex
// (the vertex lies on or beyond the new outline edge), so Devillers' queue does not
// apply; ears and flips with CGAL's exact predicates give the same constrained Delaunay
// triangulation for the handful of ring vertices an outline star has.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <vector>

#include "tinlod/importance.h"
#include "triangle_contains.h"

namespace tinlod {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

K::Point_2 xy(const Point3& p) { return K::Point_2(p.x, p.y); }

CGAL::Orientation orientation(const std::vector<Point3>& r, int a, int b, int c) {
  return CGAL::orientation(xy(r[a]), xy(r[b]), xy(r[c]));
}

// Any triangulation of the simple polygon, by clipping ears: a strictly convex corner
// whose triangle holds no other polygon vertex.
bool clipAnyEars(const std::vector<Point3>& ring, std::vector<LocalTriangle>& out) {
  std::vector<int> left(ring.size());
  for (std::size_t i = 0; i < ring.size(); ++i) left[i] = static_cast<int>(i);
  while (left.size() > 3) {
    const std::size_t m = left.size();
    bool clipped = false;
    for (std::size_t i = 0; i < m && !clipped; ++i) {
      const int a = left[(i + m - 1) % m], b = left[i], c = left[(i + 1) % m];
      if (orientation(ring, a, b, c) != CGAL::LEFT_TURN) continue;
      bool empty = true;
      for (int p : left)
        if (p != a && p != b && p != c && triangleContains(xy(ring[a]), xy(ring[b]), xy(ring[c]), xy(ring[p]))) empty = false;
      if (!empty) continue;
      out.push_back({a, b, c});
      left.erase(left.begin() + static_cast<std::ptrdiff_t>(i));
      clipped = true;
    }
    if (!clipped) return false;
  }
  if (orientation(ring, left[0], left[1], left[2]) != CGAL::LEFT_TURN) return false;
  out.push_back({left[0], left[1], left[2]});
  return true;
}

// Lawson's flips: an inner edge whose opposite corner lies strictly inside the other
// triangle's circle is replaced by the other diagonal (its quadrilateral is then convex)
// until none is left; a ring edge, the new outline edge included, is never flipped.
void flipToDelaunay(const std::vector<Point3>& ring, std::vector<LocalTriangle>& tris) {
  bool flipped = true;
  for (std::size_t rounds = 0; flipped && rounds < 4 * tris.size() * tris.size() + 4; ++rounds) {
    flipped = false;
    for (std::size_t t = 0; t < tris.size() && !flipped; ++t)
      for (int e = 0; e < 3 && !flipped; ++e) {
        const int a = tris[t][e], b = tris[t][(e + 1) % 3], c = tris[t][(e + 2) % 3];
        for (std::size_t u = 0; u < tris.size() && !flipped; ++u) {
          if (u == t) continue;
          for (int f = 0; f < 3; ++f) {
            if (tris[u][f] != b || tris[u][(f + 1) % 3] != a) continue;
            const int d = tris[u][(f + 2) % 3];
            if (CGAL::side_of_oriented_circle(xy(ring[a]), xy(ring[b]), xy(ring[c]), xy(ring[d])) !=
                CGAL::ON_POSITIVE_SIDE)
              break;
            tris[t] = {c, a, d};
            tris[u] = {d, b, c};
            flipped = true;
            break;
          }
        }
      }
  }
}

}  // namespace

bool retriangulateOpenStar(const Star& star, std::vector<LocalTriangle>& out) {
  out.clear();
  const std::vector<Point3>& ring = star.ring;
  const int d = static_cast<int>(ring.size());
  if (d < 3) return false;
  for (int i = 1; i + 1 < d; ++i)
    if (orientation(ring, d - 1, 0, i) != CGAL::LEFT_TURN) return false;
  if (!clipAnyEars(ring, out)) {
    out.clear();
    return false;
  }
  flipToDelaunay(ring, out);
  return true;
}

}  // namespace tinlod
