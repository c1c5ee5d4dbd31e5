// SPDX-License-Identifier: GPL-3.0-or-later
#include "simplification_mesh.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>

#include "tinlod/error.h"

namespace tinlod {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

K::Point_2 xy(const Point3& p) { return K::Point_2(p.x, p.y); }

const char* kNotSampled = "the level-0 TIN is not a Delaunay triangulation: it was not made by tinlod sample";

}  // namespace

// Slots are ordered by their triangles' smallest vertex id: the simplifier visits
// vertices in id order, so the stars it walks one after another lie side by side.
SimplificationMesh::SimplificationMesh(const Tin& base) {
  points_.reserve(base.vertices.size());
  for (const TinVertex& v : base.vertices) points_.push_back({v.x, v.y, v.z});
  std::vector<std::uint32_t> first(points_.size() + 1, 0);
  for (const Triangle& tri : base.triangles) {
    for (VertexId v : tri)
      if (v >= points_.size()) throw Error("internal error: a triangle names a vertex the TIN does not have");
    ++first[*std::min_element(tri.begin(), tri.end()) + 1];
  }
  for (std::size_t v = 0; v < points_.size(); ++v) first[v + 1] += first[v];
  triangles_.resize(base.triangles.size());
  for (std::size_t t = 0; t < base.triangles.size(); ++t) {
    const Triangle& tri = base.triangles[t];
    if (CGAL::orientation(xy(points_[tri[0]]), xy(points_[tri[1]]), xy(points_[tri[2]])) != CGAL::LEFT_TURN)
      throw Error(kNotSampled);
    triangles_[first[*std::min_element(tri.begin(), tri.end())]++] = {
        {std::int32_t(tri[0]), std::int32_t(tri[1]), std::int32_t(tri[2])},
        {kNoTriangle, kNoTriangle, kNoTriangle},
        static_cast<std::int32_t>(t)};
  }
  link();
  checkDelaunay();
}

// Each edge a -> b finds its twin b -> a among the triangles around b (a vertex-to-
// triangles index built by counting), so linking is linear in the TIN's size.
void SimplificationMesh::link() {
  const std::size_t nv = points_.size();
  std::vector<std::int32_t> first(nv + 1, 0);
  for (const MeshTriangle& t : triangles_)
    for (std::int32_t v : t.v) ++first[v + 1];
  for (std::size_t v = 0; v < nv; ++v) first[v + 1] += first[v];
  std::vector<std::int32_t> around(first.back()), fill(first.begin(), first.end() - 1);
  for (std::size_t t = 0; t < triangles_.size(); ++t)
    for (std::int32_t v : triangles_[t].v) around[fill[v]++] = static_cast<std::int32_t>(t);

  start_.assign(nv, kNoTriangle);
  open_.assign(nv, 1);
  for (std::size_t v = 0; v < nv; ++v)
    if (first[v] < first[v + 1]) start_[v] = around[first[v]], open_[v] = 0;
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    MeshTriangle& tri = triangles_[t];
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = tri.v[(k + 1) % 3], b = tri.v[(k + 2) % 3];
      for (std::int32_t i = first[b]; i < first[b + 1]; ++i) {
        const MeshTriangle& other = triangles_[around[i]];
        const int j = other.v[0] == b ? 0 : other.v[1] == b ? 1 : 2;
        if (other.v[(j + 1) % 3] != a) continue;
        if (tri.n[k] != kNoTriangle) throw Error(kNotSampled);  // an edge of three triangles
        tri.n[k] = around[i];
      }
      if (tri.n[k] == kNoTriangle) open_[a] = open_[b] = 1;
    }
  }
}

void SimplificationMesh::checkDelaunay() const {
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    const MeshTriangle& tri = triangles_[t];
    for (int k = 0; k < 3; ++k) {
      const std::int32_t u = tri.n[k];
      if (u < static_cast<std::int32_t>(t)) continue;  // each shared edge once; none across the outline
      const MeshTriangle& other = triangles_[u];
      const int j = other.n[0] == std::int32_t(t) ? 0 : other.n[1] == std::int32_t(t) ? 1 : 2;
      if (CGAL::side_of_oriented_circle(xy(points_[tri.v[0]]), xy(points_[tri.v[1]]), xy(points_[tri.v[2]]),
                                        xy(points_[other.v[j]])) == CGAL::ON_POSITIVE_SIDE)
        throw Error(kNotSampled);
    }
  }
}

int SimplificationMesh::degree(VertexId v) const {
  int d = 0;
  eachAround(v, [&](std::int32_t, int) { ++d; });
  return d;
}

// Visits (slot, k) around v starting at the slot whose next ring vertex has the
// smallest id. One walk, kept, then visited from there: the walk is the costly part.
template <class Visit>
void SimplificationMesh::canonicalWalk(VertexId v, Visit visit) const {
  thread_local std::vector<std::pair<std::int32_t, int>> around;
  around.clear();
  std::size_t best = 0;
  std::int32_t bestId = 0;
  eachAround(v, [&](std::int32_t t, int k) {
    const std::int32_t id = triangles_[t].v[(k + 1) % 3];
    if (around.empty() || id < bestId) best = around.size(), bestId = id;
    around.emplace_back(t, k);
  });
  for (std::size_t i = best; i < around.size(); ++i) visit(around[i].first, around[i].second);
  for (std::size_t i = 0; i < best; ++i) visit(around[i].first, around[i].second);
}

void SimplificationMesh::starOf(VertexId v, VertexId* ring, std::int32_t* slots, std::int32_t* outer) const {
  int i = 0;
  canonicalWalk(v, [&](std::int32_t t, int k) {
    const MeshTriangle& tri = triangles_[t];
    ring[i] = static_cast<VertexId>(tri.v[(k + 1) % 3]);
    slots[i] = t;
    outer[i++] = tri.n[k];
  });
}

void SimplificationMesh::geometryOf(VertexId v, Star& star) const {
  star.centre = points_[v];
  star.ring.clear();
  canonicalWalk(v, [&](std::int32_t t, int k) { star.ring.push_back(points_[triangles_[t].v[(k + 1) % 3]]); });
}

void SimplificationMesh::beginRound() {
  if (successor_.empty()) successor_.assign(triangles_.size(), kNoTriangle), retired_.assign(triangles_.size(), 0);
  ++round_;
}

void SimplificationMesh::retire(const StarView& star, const LocalTriangle* fill) {
  const int d = star.degree;
  for (int j = 0; j + 2 < d; ++j)
    for (int e = 0; e < 3; ++e) {
      const int p = fill[j][e], q = fill[j][(e + 1) % 3];
      if (q != (p + 1) % d) continue;
      successor_[star.slots[p]] = star.slots[j];
      retired_[star.slots[p]] = round_;
    }
}

// Diagonals pair up through `owner`, indexed by directed edge (p, q) of local ring
// indices. A ring edge faces the triangle beyond it, or that triangle's successor when
// its own star is being replaced too (which then links back by itself).
void SimplificationMesh::replaceStar(const StarView& star, const LocalTriangle* fill, const std::int32_t* ids) {
  const int d = star.degree;
  thread_local std::vector<std::int32_t> owner;
  if (owner.size() < static_cast<std::size_t>(d) * d) owner.resize(static_cast<std::size_t>(d) * d);
  for (int j = 0; j + 2 < d; ++j)
    for (int e = 0; e < 3; ++e) owner[fill[j][e] * d + fill[j][(e + 1) % 3]] = star.slots[j];
  for (int j = 0; j + 2 < d; ++j) {
    const std::int32_t slot = star.slots[j];
    MeshTriangle& tri = triangles_[slot];
    tri.id = ids[j];
    for (int e = 0; e < 3; ++e) {
      const int p = fill[j][(e + 1) % 3], q = fill[j][(e + 2) % 3];  // the edge opposite corner e
      const VertexId corner = star.ring[fill[j][e]];
      tri.v[e] = static_cast<std::int32_t>(corner);
      // Stars that share a ring vertex race here; either new triangle is a right answer.
      __atomic_store_n(&start_[corner], slot, __ATOMIC_RELAXED);
      if (q != (p + 1) % d) {
        tri.n[e] = owner[q * d + p];
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
  for (int k = d - 2; k < d; ++k) triangles_[star.slots[k]].v = {-1, -1, -1};
}

}  // namespace tinlod
