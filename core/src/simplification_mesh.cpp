// SPDX-License-Identifier: GPL-3.0-or-later
#include "simplification_mesh.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <atomic>

#include "compact_in_place.h"
#include "parallel_blocks.h"
#include "release_memory.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

K::Point_2 xy(const Point3& p) { return K::Point_2(p.x, p.y); }

const char* kNotSampled = "the level-0 TIN is not a Delaunay triangulation: it was not made by tinlod sample";

}  // namespace

SimplificationMesh::SimplificationMesh(const Tin& base) {
  vertices_ = base.vertices.data(), vertexCount_ = base.vertices.size();
  for (const Triangle& tri : base.triangles)
    for (VertexId v : tri)
      if (v >= vertexCount_) throw Error("internal error: a triangle names a vertex the TIN does not have");
  Compaction& order = compaction_;
  orderBySmallestVertex(base.triangles.size(), vertexCount_, [&](std::size_t t) {
    return static_cast<std::int32_t>(*std::min_element(base.triangles[t].begin(), base.triangles[t].end()));
  }, order, tallies_);
  linkedFromNeighbours_ = fill(base) && checkDelaunay();
  if (!linkedFromNeighbours_) {
    for (MeshTriangle& t : triangles_) t.n = {kNoTriangle, kNoTriangle, kNoTriangle};
    link();
    if (!checkDelaunay()) throw Error(kNotSampled);
  }
  indexVertices();
  endCompaction();
}

// The triangles in their new order, on every core; linked as the triangulation's own
// neighbours say when the TIN still has them (which spares the search for each edge's
// twin). Returns true when it has them, all in range; checkDelaunay then verifies that
// each link comes back. An outline edge is taken as the neighbours say: they come from
// the sampler's triangulation.
bool SimplificationMesh::fill(const Tin& base) {
  const Compaction& order = compaction_;
  const int count = static_cast<int>(base.triangles.size());
  const bool given = base.neighbours.size() == base.triangles.size();
  std::atomic<bool> fits{given};
  triangles_.resize(base.triangles.size());
  forEachBlock(count, [&](int begin, int end) {
    for (int slot = begin; slot < end; ++slot) {
      const std::int32_t t = order.oldOf[slot];
      const Triangle& tri = base.triangles[t];
      MeshTriangle& m = triangles_[slot];
      m = {{std::int32_t(tri[0]), std::int32_t(tri[1]), std::int32_t(tri[2])}, {kNoTriangle, kNoTriangle, kNoTriangle}, t};
      if (!given) continue;
      for (int k = 0; k < 3; ++k) {
        const std::int32_t u = base.neighbours[t][k];
        if (u >= count) fits = false;
        m.n[k] = u < 0 || u >= count ? kNoTriangle : order.newOf[u];
      }
    }
  }, {});
  return fits;
}

// Each edge a -> b finds its twin b -> a among the half-edges leaving b, listed per
// vertex by counting: linear in the TIN's size, and the lists are compact to scan.
void SimplificationMesh::link() {
  const std::size_t nv = vertexCount_;
  const int count = static_cast<int>(triangles_.size());
  struct HalfEdge {
    std::int32_t head, corner;  // corner: slot * 3 + the corner opposite the edge
  };
  std::vector<std::int32_t> first(nv + 1, 0);
  for (const MeshTriangle& t : triangles_)
    for (std::int32_t v : t.v) ++first[v + 1];
  for (std::size_t v = 0; v < nv; ++v) first[v + 1] += first[v];
  std::vector<HalfEdge> out(first.back());
  std::vector<std::int32_t> fill(first.begin(), first.end() - 1);
  for (int t = 0; t < count; ++t)
    for (int k = 0; k < 3; ++k) out[fill[triangles_[t].v[(k + 1) % 3]]++] = {triangles_[t].v[(k + 2) % 3], t * 3 + k};
  // Two triangles on the same side of an edge overlap: the edge then finds its twin twice
  // (thrown here), or its twin links back to only one of them (found by checkDelaunay),
  // or, on the outline, a's list holds the edge twice.
  auto heads = [&](std::int32_t from, std::int32_t to) {
    return std::count_if(out.begin() + first[from], out.begin() + first[from + 1],
                         [to](const HalfEdge& h) { return h.head == to; });
  };
  forEachBlock(count, [&](int begin, int end) {
    for (int t = begin; t < end; ++t)
      for (int k = 0; k < 3; ++k) {
        const std::int32_t a = triangles_[t].v[(k + 1) % 3], b = triangles_[t].v[(k + 2) % 3];
        int twins = 0;
        for (std::int32_t i = first[b]; i < first[b + 1]; ++i)
          if (out[i].head == a) triangles_[t].n[k] = out[i].corner / 3, ++twins;
        if (twins > 1 || (twins == 0 && heads(a, b) != 1)) throw Error(kNotSampled);
      }
  }, {});
}

// Each vertex's first triangle, whether it is open (on an outline edge, or in no
// triangle), and the check that a closed vertex has one fan of all its triangles: two
// fans meeting at a vertex would be deleted as one star. An open vertex whose triangles
// make one fan of two or more may be deleted; one where fans meet may not.
void SimplificationMesh::indexVertices() {
  const std::size_t nv = vertexCount_;
  std::vector<std::int32_t> triangles(nv, 0);
  start_.assign(nv, kNoTriangle);
  open_.assign(nv, kClosed);
  for (std::size_t t = 0; t < triangles_.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const MeshTriangle& tri = triangles_[t];
      ++triangles[tri.v[k]];
      start_[tri.v[k]] = static_cast<std::int32_t>(t);
      if (tri.n[k] == kNoTriangle) open_[tri.v[(k + 1) % 3]] = open_[tri.v[(k + 2) % 3]] = kOpen;
    }
  for (std::size_t v = 0; v < nv; ++v)
    if (triangles[v] == 0) open_[v] = kOpen;
  forEachBlock(static_cast<int>(nv), [&](int begin, int end) {
    for (int v = begin; v < end; ++v) {
      if (open_[v] == kClosed) {
        if (degree(static_cast<VertexId>(v)) != triangles[v]) throw Error(kNotSampled);
        continue;
      }
      if (triangles[v] < 2) continue;
      int fan = 0;
      aroundOpen(v, [&](std::int32_t, int) { ++fan; });
      if (fan == triangles[v]) open_[v] = kOneFan;
    }
  }, {});
}

// Each link first, so that the in-circle test never meets a stale neighbour: returns
// false when a link does not come back across the same edge (two triangles on one side
// of it, or neighbours the triangles no longer match).
bool SimplificationMesh::checkDelaunay() const {
  std::atomic<bool> linked{true};
  forEachBlock(static_cast<int>(triangles_.size()), [&](int begin, int end) {
    for (int t = begin; t < end && linked; ++t) {
      const MeshTriangle& tri = triangles_[t];
      int twin[3];
      for (int k = 0; k < 3; ++k)
        if (tri.n[k] != kNoTriangle && (twin[k] = twinCorner(t, k)) < 0) return void(linked = false);
      const K::Point_2 a = xy(point(tri.v[0])), b = xy(point(tri.v[1])), c = xy(point(tri.v[2]));
      if (CGAL::orientation(a, b, c) != CGAL::LEFT_TURN) throw Error(kNotSampled);
      for (int k = 0; k < 3; ++k) {
        const std::int32_t u = tri.n[k];
        if (u == kNoTriangle || u < t) continue;  // each shared edge's in-circle test once
        if (CGAL::side_of_oriented_circle(a, b, c, xy(point(triangles_[u].v[twin[k]]))) == CGAL::ON_POSITIVE_SIDE)
          throw Error(kNotSampled);
      }
    }
  }, {});
  return linked;
}

int SimplificationMesh::degree(VertexId v) const {
  int d = open_[v] ? 1 : 0;
  eachAround(v, [&](std::int32_t, int) { ++d; });
  return d;
}

VertexId SimplificationMesh::outlineAfter(VertexId v) const {
  const MeshTriangle& tri = triangles_[firstOpen(static_cast<std::int32_t>(v))];
  const int k = tri.v[0] == std::int32_t(v) ? 0 : tri.v[1] == std::int32_t(v) ? 1 : 2;
  return static_cast<VertexId>(tri.v[(k + 1) % 3]);
}

VertexId SimplificationMesh::outlineBefore(VertexId v) const {
  VertexId last = 0;
  aroundOpen(static_cast<std::int32_t>(v), [&](std::int32_t t, int k) { last = static_cast<VertexId>(triangles_[t].v[(k + 2) % 3]); });
  return last;
}

// Visits (slot, k) around v starting at the slot whose next ring vertex has the
// smallest id.
template <class Visit>
void SimplificationMesh::canonicalWalk(VertexId v, Visit visit) const {
  std::int32_t best = kNoTriangle, bestId = 0;
  eachAround(v, [&](std::int32_t t, int k) {
    const std::int32_t id = triangles_[t].v[(k + 1) % 3];
    if (best == kNoTriangle || id < bestId) best = t, bestId = id;
  });
  aroundFrom(static_cast<std::int32_t>(v), best, visit);  // the second walk finds every triangle in cache
}

void SimplificationMesh::starOf(VertexId v, VertexId* ring, std::int32_t* slots, std::int32_t* outer,
                                Star& geometry) const {
  int i = 0;
  geometry.centre = point(v);
  geometry.ring.clear();
  geometry.open = open_[v] != kClosed;
  auto visit = [&](std::int32_t t, int k) {
    const MeshTriangle& tri = triangles_[t];
    ring[i] = static_cast<VertexId>(tri.v[(k + 1) % 3]);
    geometry.ring.push_back(point(tri.v[(k + 1) % 3]));
    slots[i] = t;
    outer[i++] = tri.n[k];
  };
  if (!geometry.open) return canonicalWalk(v, visit);
  std::int32_t last = kNoTriangle;
  aroundOpen(static_cast<std::int32_t>(v), [&](std::int32_t t, int k) { visit(t, k), last = triangles_[t].v[(k + 2) % 3]; });
  ring[i] = static_cast<VertexId>(last);
  geometry.ring.push_back(point(last));
  slots[i] = kNoTriangle;
  outer[i] = kNoTriangle;
}

// One walk into a small buffer, then the points from the smallest ring vertex on: the
// importance reads millions of stars, and a second walk costs a sixth of it.
int SimplificationMesh::geometryOf(VertexId v, Star& star, VertexId* ids, int capacity) const {
  std::int32_t ring[kSmallStar];
  int d = 0;
  star.centre = point(v);
  star.ring.clear();
  star.open = open_[v] != kClosed;
  if (star.open) {
    std::int32_t last = kNoTriangle;
    aroundOpen(static_cast<std::int32_t>(v), [&](std::int32_t t, int k) {
      const MeshTriangle& tri = triangles_[t];
      if (d < capacity) ids[d] = static_cast<VertexId>(tri.v[(k + 1) % 3]);
      star.ring.push_back(point(tri.v[(k + 1) % 3]));
      last = tri.v[(k + 2) % 3];
      ++d;
    });
    if (d < capacity) ids[d] = static_cast<VertexId>(last);
    star.ring.push_back(point(last));
    return d + 1;
  }
  eachAround(v, [&](std::int32_t t, int k) {
    if (d < kSmallStar) ring[d] = triangles_[t].v[(k + 1) % 3];
    ++d;
  });
  if (d > kSmallStar) {
    canonicalWalk(v, [&](std::int32_t t, int k) { star.ring.push_back(point(triangles_[t].v[(k + 1) % 3])); });
    return d;
  }
  const int first = static_cast<int>(std::min_element(ring, ring + d) - ring);
  star.ring.resize(d);
  for (int i = 0; i < d; ++i) star.ring[i] = point(ring[(first + i) % d]);
  if (d <= capacity)
    for (int i = 0; i < d; ++i) ids[i] = static_cast<VertexId>(ring[(first + i) % d]);
  return d;
}

// Entries of earlier rounds, even from before a compaction, carry an older round number.
void SimplificationMesh::beginRound() {
  successor_.resize(triangles_.size(), kNoTriangle);
  retired_.resize(triangles_.size(), 0);
  releaseUnusedCapacity(successor_), releaseUnusedCapacity(retired_);  // the mesh shrank
  ++round_;
}

// Ordered by smallest vertex again, as level 0 was: new triangles left where their stars
// were drift from the order the vertices are visited in. The triangles move in place and
// the pages past the new end are given back: a copy would hold the mesh twice at the
// level's peak.
const Compaction& SimplificationMesh::planCompaction() {
  Compaction& c = compaction_;
  orderBySmallestVertex(triangles_.size(), vertexCount_, [&](std::size_t t) {
    const MeshTriangle& tri = triangles_[t];
    return tri.v[0] < 0 ? -1 : std::min({tri.v[0], tri.v[1], tri.v[2]});
  }, c, tallies_);
  return c;
}

void SimplificationMesh::applyCompaction() {
  const Compaction& c = compaction_;
  compactInPlace(triangles_, c);
  forEachBlock(static_cast<int>(triangles_.size()), [&](int begin, int end) {
    for (int slot = begin; slot < end; ++slot)
      for (std::int32_t& n : triangles_[slot].n)
        if (n != kNoTriangle) n = c.newOf[n];
  }, {});
  for (std::size_t t = 0; t < triangles_.size(); ++t)
    for (std::int32_t v : triangles_[t].v) start_[v] = static_cast<std::int32_t>(t);
}

void SimplificationMesh::endCompaction() {
  releaseMemory(compaction_.oldOf), releaseMemory(compaction_.newOf);
  releaseMemory(tallies_[0]), releaseMemory(tallies_[1]);
}

std::size_t SimplificationMesh::liveTriangles() const {
  return static_cast<std::size_t>(
      std::count_if(triangles_.begin(), triangles_.end(), [](const MeshTriangle& t) { return t.v[0] >= 0; }));
}

int SimplificationMesh::twinCorner(std::int32_t t, int k) const {
  const MeshTriangle& tri = triangles_[t];
  const MeshTriangle& other = triangles_[tri.n[k]];
  const std::int32_t a = tri.v[(k + 1) % 3], b = tri.v[(k + 2) % 3];
  for (int j = 0; j < 3; ++j)
    if (other.n[j] == t && other.v[(j + 1) % 3] == b && other.v[(j + 2) % 3] == a) return j;
  return -1;
}

std::size_t SimplificationMesh::brokenLinks() const {
  std::size_t broken = 0;
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    if (triangles_[t].v[0] < 0) continue;
    for (int k = 0; k < 3; ++k)
      broken += triangles_[t].n[k] != kNoTriangle && twinCorner(static_cast<std::int32_t>(t), k) < 0;
  }
  return broken;
}

void SimplificationMesh::retire(const StarView& star, const int* onEdge) {
  for (int k = 0; k < star.triangles(); ++k) {
    successor_[star.slots[k]] = star.slots[onEdge[k]];
    retired_[star.slots[k]] = round_;
  }
}

// Diagonals pair up by directed edge (p, q) of local ring indices: through a d x d table
// for usual stars, through sorted keys for a huge one. A ring edge faces the triangle
// beyond it, or that triangle's successor when its own star is being replaced too (which
// then links back by itself). No walk runs before applyCompaction(), which sets start_ again.
void SimplificationMesh::replaceStar(const StarView& star, const LocalTriangle* fill, const std::int32_t* ids) {
  const int d = star.degree;
  const bool small = d <= kSmallStar;
  thread_local std::vector<std::int32_t> table;
  thread_local std::vector<std::pair<std::uint64_t, std::int32_t>> sorted;
  auto key = [d](int p, int q) { return static_cast<std::uint64_t>(p) * static_cast<std::uint64_t>(d) + q; };
  if (small) table.resize(static_cast<std::size_t>(d) * d);
  else sorted.clear();
  for (int j = 0; j + 2 < d; ++j)
    for (int e = 0; e < 3; ++e) {
      const std::uint64_t k = key(fill[j][e], fill[j][(e + 1) % 3]);
      if (small) table[k] = star.slots[j];
      else sorted.emplace_back(k, star.slots[j]);
    }
  if (!small) std::sort(sorted.begin(), sorted.end());
  auto owner = [&](int p, int q) {
    if (small) return table[key(p, q)];
    return std::lower_bound(sorted.begin(), sorted.end(), std::make_pair(key(p, q), std::int32_t{-1}))->second;
  };
  for (int j = 0; j + 2 < d; ++j) {
    const std::int32_t slot = star.slots[j];
    MeshTriangle& tri = triangles_[slot];
    tri.id = ids[j];
    for (int e = 0; e < 3; ++e) {
      const int p = fill[j][(e + 1) % 3], q = fill[j][(e + 2) % 3];  // the edge opposite corner e
      tri.v[e] = static_cast<std::int32_t>(star.ring[fill[j][e]]);
      if (q != (p + 1) % d) {
        tri.n[e] = owner(q, p);
        continue;
      }
      const std::int32_t beyond = star.outer[p];
      if (beyond != kNoTriangle && retired_[beyond] == round_) {
        tri.n[e] = successor_[beyond];
        continue;
      }
      tri.n[e] = beyond;
      if (beyond == kNoTriangle) continue;
      MeshTriangle& b = triangles_[beyond];
      const std::int32_t head = static_cast<std::int32_t>(star.ring[q]);
      b.n[b.v[1] == head ? 0 : b.v[2] == head ? 1 : 2] = slot;
    }
  }
  for (int k = d - 2; k < star.triangles(); ++k) triangles_[star.slots[k]].v = {-1, -1, -1};
}

}  // namespace tinlod
