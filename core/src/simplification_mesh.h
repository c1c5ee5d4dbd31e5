// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the TIN the delete simplification works on, as flat arrays of triangles with
// their neighbours. CGAL's triangulation is a general structure (infinite faces, handles
// in a container, a remove() that checks dimensions and degrees); the simplifier only
// ever deletes interior vertices of an independent set, and flat arrays in the TIN's own
// order keep each star walk in cache. Predicates stay CGAL's exact ones.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "tinlod/importance.h"
#include "tinlod/tin.h"

namespace tinlod {

constexpr std::int32_t kNoTriangle = -1;

struct MeshTriangle {
  std::array<std::int32_t, 3> v;  // vertex ids, counter-clockwise; v[0] < 0 for a dead slot
  std::array<std::int32_t, 3> n;  // n[k]: the triangle across the edge opposite v[k], or kNoTriangle
  std::int32_t id;                // the triangle's id in the hierarchy
};

// A vertex's star as the simplifier needs it: ring[k], ring[k + 1] and the vertex make
// slots[k], counter-clockwise.
struct MeshStar {
  std::vector<VertexId> ring;
  std::vector<std::int32_t> slots;
};

class SimplificationMesh {
 public:
  // Level 0: the TIN's triangles, whose index becomes their id. Throws Error when a
  // triangle is not counter-clockwise, an edge has more than two triangles, or an edge is
  // not locally Delaunay (exact in-circle): such a TIN was not made by tinlod sample.
  explicit SimplificationMesh(const Tin& base);

  const Point3& point(VertexId v) const { return points_[v]; }
  const MeshTriangle& triangle(std::int32_t slot) const { return triangles_[slot]; }
  std::size_t slotCount() const { return triangles_.size(); }
  // True for a vertex on the outline or a hole's edge, or in no triangle: it has no
  // closed star and is never deleted.
  bool open(VertexId v) const { return open_[v] != 0; }

  // Calls visit(slot, k) for each triangle around an interior vertex, counter-clockwise,
  // where k is the vertex's index in the triangle.
  template <class Visit>
  void eachAround(VertexId v, Visit visit) const {
    const std::int32_t first = start_[v];
    std::int32_t t = first;
    do {
      const MeshTriangle& tri = triangles_[t];
      const int k = tri.v[0] == static_cast<std::int32_t>(v) ? 0 : tri.v[1] == static_cast<std::int32_t>(v) ? 1 : 2;
      visit(t, k);
      t = tri.n[(k + 1) % 3];
    } while (t != first);
  }
  int degree(VertexId v) const;
  void starOf(VertexId v, MeshStar& star) const;
  void geometryOf(VertexId v, Star& star) const;  // the same star as points, for importance

  // Deletes an interior vertex: `fill` (ring.size() - 2 triangles of local indices, from
  // retriangulateStar) triangulates its star's ring. The new triangles take the first
  // star slots, in fill's order, with `ids` as their hierarchy ids; the last two slots die.
  void replaceStar(const MeshStar& star, const LocalTriangle* fill, const std::int32_t* ids);

 private:
  void link();
  void checkDelaunay() const;

  std::vector<Point3> points_;
  std::vector<MeshTriangle> triangles_;
  std::vector<std::int32_t> start_;  // by vertex: one triangle around it
  std::vector<std::uint8_t> open_;
  std::vector<std::int32_t> owner_;  // scratch of replaceStar: the new triangle of each ring edge
};

}  // namespace tinlod
