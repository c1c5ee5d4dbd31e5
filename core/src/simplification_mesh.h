// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the TIN the delete simplification works on, as flat arrays of triangles with
// their neighbours. CGAL's triangulation is a general structure (infinite faces, handles
// in a container, a remove() that checks dimensions and degrees, one vertex at a time);
// the simplifier only ever deletes vertices of an independent set, whose stars are
// disjoint, so here a whole set is deleted in two passes that each run on every core,
// and the arrays, in the TIN's own order, keep each star walk in cache. Predicates stay
// CGAL's exact ones.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "smallest_vertex_order.h"
#include "tinlod/importance.h"
#include "tinlod/tin.h"

namespace tinlod {

constexpr std::int32_t kNoTriangle = -1;
constexpr int kSmallStar = 64;  // stars of up to this degree are handled in fixed-size scratch

struct MeshTriangle {
  std::array<std::int32_t, 3> v;  // TIN vertex ids, counter-clockwise; v[0] < 0 for a dead slot
  std::array<std::int32_t, 3> n;  // n[k]: the triangle across the edge opposite v[k], or kNoTriangle
  std::int32_t id;                // the triangle's id in the hierarchy
};

// A vertex's star, `degree` ring vertices long: ring[k], ring[k + 1] and the vertex make
// slots[k], counter-clockwise, and outer[k] is the triangle beyond ring edge k (or
// kNoTriangle). An interior vertex's ring is closed and starts at its smallest vertex id,
// so nothing computed from a star depends on where a walk happened to start. An outline
// vertex's ring is open: it runs from the outline neighbour after the vertex to the one
// before it (counter-clockwise around the vertex), so it has degree - 1 triangles, and
// its last ring edge, from the last ring vertex back to the first, is the outline edge
// that replaces the vertex (slots and outer there are kNoTriangle).
struct StarView {
  const VertexId* ring;
  const std::int32_t* slots;
  const std::int32_t* outer;
  int degree;
  bool open = false;
  int triangles() const { return open ? degree - 1 : degree; }
};

class SimplificationMesh {
 public:
  // Level 0: the TIN's triangles, whose index becomes their id. Throws Error when a
  // triangle is not counter-clockwise, an edge has more than two triangles, or an edge is
  // not locally Delaunay (exact in-circle): such a TIN was not made by tinlod sample.
  // `base` must outlive the mesh: its vertices are read where they are (a copy of their
  // positions would cost 24 bytes a vertex, 45 MB on a 4096 x 4096 tile).
  explicit SimplificationMesh(const Tin& base);
  SimplificationMesh() = default;  // no triangles

  // Vertices are named by their TIN ids throughout: deleted ones simply drop out of the
  // triangles. (Numbering the vertices left densely at each level saved no time.)
  Point3 point(VertexId v) const {
    const TinVertex& p = vertices_[v];
    return {p.x, p.y, p.z};
  }
  std::int32_t triangleId(std::int32_t slot) const { return triangles_[slot].id; }
  VertexId corner(std::int32_t slot, int k) const { return static_cast<VertexId>(triangles_[slot].v[k]); }
  // The triangle across the edge opposite corner k, or kNoTriangle on the outline.
  std::int32_t across(std::int32_t slot, int k) const { return triangles_[slot].n[k]; }
  std::size_t slots() const { return triangles_.size(); }
  // True for a vertex on the outline or a hole's edge, or in no triangle: it has no
  // closed star.
  bool open(VertexId v) const { return open_[v] != 0; }
  // An open vertex whose triangles make one fan of two or more: its star can be deleted,
  // the outline then going straight from one of its outline neighbours to the other. A
  // vertex where two fans meet (two parts of the TIN touching) cannot.
  bool deletableOpen(VertexId v) const { return open_[v] == kOneFan; }
  bool inTriangle(VertexId v) const { return start_[v] != kNoTriangle; }

  // Calls visit(slot, k) for each triangle around a vertex, counter-clockwise, where k is
  // the vertex's index in the triangle: around an interior vertex from wherever the walk
  // starts, around an open one from its first triangle after the outline.
  template <class Visit>
  void eachAround(VertexId v, Visit visit) const {
    if (open_[v]) aroundOpen(static_cast<std::int32_t>(v), visit);
    else aroundFrom(static_cast<std::int32_t>(v), start_[v], visit);
  }
  // The number of ring vertices: of triangles around an interior vertex, one more around
  // an open one.
  int degree(VertexId v) const;
  // Along the outline with the TIN's data on the left, the vertex before and after v (an
  // open vertex of one fan).
  VertexId outlineBefore(VertexId v) const;
  VertexId outlineAfter(VertexId v) const;
  // Star walks wait on memory: a loop over many vertices asks for the entry of the
  // vertex `far` ahead and for the first triangle and point of the one `near` ahead
  // (whose entry then is there), 5 % off the whole build on alps_2x2.
  template <class VertexAt>
  void prefetchAhead(int i, int end, VertexAt vertexAt) const {
    constexpr int near = 8, far = 16;
    if (i + far < end) __builtin_prefetch(&start_[vertexAt(i + far)]);
    if (i + near < end) {
      const VertexId v = vertexAt(i + near);
      __builtin_prefetch(&triangles_[start_[v]]), __builtin_prefetch(&vertices_[v]);
    }
  }
  // Writes the star of a vertex (interior, or open of one fan) into arrays of degree(v)
  // entries each, and its points into `geometry`.
  void starOf(VertexId v, VertexId* ring, std::int32_t* slots, std::int32_t* outer, Star& geometry) const;
  // The same ring as points, for importance, and as TIN ids in `ids` when the degree
  // (returned) is at most `capacity`.
  int geometryOf(VertexId v, Star& star, VertexId* ids, int capacity) const;

  // Deleting an independent set: beginRound(), then retire() for every star (it only
  // reads the triangles), then replaceStar() for every star, each on any thread, then
  // planCompaction() and applyCompaction() before the next walk. `fill` (degree - 2
  // triangles of local ring indices, from retriangulateStar) triangulates the ring, and
  // `onEdge` is its ringEdgeTriangles(); the new triangles take the first star slots, in
  // fill's order, with `ids` as their hierarchy ids, and the rest of the slots die (two
  // for an interior vertex, one for an open one).
  void beginRound();
  void retire(const StarView& star, const int* onEdge);
  void replaceStar(const StarView& star, const LocalTriangle* fill, const std::int32_t* ids);
  // Drops the dead slots and orders the rest by smallest vertex again, so that the stars
  // of the vertices still there stay side by side in memory as the TIN thins out:
  // planCompaction() numbers them anew (the result is valid until endCompaction(),
  // and others may use it while) applyCompaction() moves them.
  const Compaction& planCompaction();
  void applyCompaction();
  // Frees the numbering and its sort's tallies (by slot and by vertex: 45 MB after level 1
  // of a 4096 x 4096 tile), held otherwise through the next level while the hierarchy
  // grows; the next compaction makes them anew.
  void endCompaction();

  // The live triangles, and how many of their links are wrong (a neighbour that does not
  // share the edge or does not link back): for the tests.
  std::size_t liveTriangles() const;
  std::size_t brokenLinks() const;
  bool linkedFromNeighbours() const { return linkedFromNeighbours_; }  // or by the edge search

 private:
  bool fill(const Tin& base);
  void link();
  void indexVertices();
  bool checkDelaunay() const;
  // Where the triangle across edge k of t has t, linked back across the same edge: the
  // corner opposite that edge there, or -1.
  int twinCorner(std::int32_t t, int k) const;
  // From triangle `first`, which must hold vertex v.
  template <class Visit>
  void aroundFrom(std::int32_t v, std::int32_t first, Visit visit) const {
    std::int32_t t = first;
    do {
      const MeshTriangle& tri = triangles_[t];
      const int k = tri.v[0] == v ? 0 : tri.v[1] == v ? 1 : 2;
      visit(t, k);
      t = tri.n[(k + 1) % 3];
    } while (t != first);
  }
  template <class Visit>
  void canonicalWalk(VertexId v, Visit visit) const;
  // From an open vertex's first triangle (the one whose edge to the vertex before it is
  // on the outline) to its last.
  std::int32_t firstOpen(std::int32_t v) const {
    std::int32_t t = start_[v];
    for (;;) {
      const MeshTriangle& tri = triangles_[t];
      const int k = tri.v[0] == v ? 0 : tri.v[1] == v ? 1 : 2;
      const std::int32_t before = tri.n[(k + 2) % 3];
      if (before == kNoTriangle) return t;
      t = before;
    }
  }
  template <class Visit>
  void aroundOpen(std::int32_t v, Visit visit) const {
    for (std::int32_t t = firstOpen(v); t != kNoTriangle;) {
      const MeshTriangle& tri = triangles_[t];
      const int k = tri.v[0] == v ? 0 : tri.v[1] == v ? 1 : 2;
      visit(t, k);
      t = tri.n[(k + 1) % 3];
    }
  }
  enum : std::uint8_t { kClosed = 0, kOpen = 1, kOneFan = 2 };

  const TinVertex* vertices_ = nullptr;  // the base TIN's, by TIN id
  std::size_t vertexCount_ = 0;
  std::vector<MeshTriangle> triangles_;
  std::vector<std::int32_t> start_;      // by TIN id: one triangle around it
  std::vector<std::uint8_t> open_;       // by TIN id: kClosed, kOpen or kOneFan
  std::vector<std::int32_t> successor_;  // by slot retired this round: the new slot holding its ring edge
  std::vector<std::uint32_t> retired_;   // by slot: the round that retired it
  std::uint32_t round_ = 0;
  bool linkedFromNeighbours_ = false;
  // The last compaction's arrays (and level 0's order), until endCompaction().
  Compaction compaction_;
  VertexTallies tallies_;
};

}  // namespace tinlod
