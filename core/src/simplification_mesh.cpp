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

void SimplificationMesh::starOf(VertexId v, MeshStar& star) const {
  star.ring.clear();
  star.slots.clear();
  eachAround(v, [&](std::int32_t t, int k) {
    star.ring.push_back(static_cast<VertexId>(triangles_[t].v[(k + 1) % 3]));
    star.slots.push_back(t);
  });
}

void SimplificationMesh::geometryOf(VertexId v, Star& star) const {
  star.centre = points_[v];
  star.ring.clear();
  eachAround(v, [&](std::int32_t t, int k) { star.ring.push_back(points_[triangles_[t].v[(k + 1) % 3]]); });
}

// Ring edge k (ring[k] -> ring[k + 1]) is the edge of slots[k] opposite the vertex; the
// triangle beyond it now faces the new triangle that has that edge. Diagonals pair up
// through `owner_`, indexed by directed edge (p, q) of local ring indices.
void SimplificationMesh::replaceStar(const MeshStar& star, const LocalTriangle* fill, const std::int32_t* ids) {
  const int d = static_cast<int>(star.ring.size());
  const std::size_t count = star.ring.size() - 2;
  std::array<std::int32_t, 64> outerSmall;
  std::vector<std::int32_t> outerLarge;
  std::int32_t* outer = outerSmall.data();
  if (d > 64) outerLarge.resize(d), outer = outerLarge.data();
  for (int k = 0; k < d; ++k) {
    const MeshTriangle& tri = triangles_[star.slots[k]];
    const std::int32_t a = static_cast<std::int32_t>(star.ring[k]);
    const int i = tri.v[0] == a ? 0 : tri.v[1] == a ? 1 : 2;  // a follows the vertex: the edge is opposite it
    outer[k] = tri.n[(i + 2) % 3];
  }
  if (owner_.size() < static_cast<std::size_t>(d) * d) owner_.resize(static_cast<std::size_t>(d) * d);
  for (std::size_t j = 0; j < count; ++j)
    for (int e = 0; e < 3; ++e) owner_[fill[j][e] * d + fill[j][(e + 1) % 3]] = star.slots[j];
  for (std::size_t j = 0; j < count; ++j) {
    const std::int32_t slot = star.slots[j];
    MeshTriangle& tri = triangles_[slot];
    tri.id = ids[j];
    for (int e = 0; e < 3; ++e) {
      const int p = fill[j][(e + 1) % 3], q = fill[j][(e + 2) % 3];  // the edge opposite corner e
      tri.v[e] = static_cast<std::int32_t>(star.ring[fill[j][e]]);
      start_[star.ring[fill[j][e]]] = slot;
      if (q != (p + 1) % d) {
        tri.n[e] = owner_[q * d + p];
        continue;
      }
      const std::int32_t beyond = outer[p];
      tri.n[e] = beyond;
      if (beyond == kNoTriangle) continue;
      // Found by its edge, not by the old slot, which a new triangle may have taken.
      MeshTriangle& b = triangles_[beyond];
      const std::int32_t head = static_cast<std::int32_t>(star.ring[q]);
      b.n[b.v[1] == head ? 0 : b.v[2] == head ? 1 : 2] = slot;
    }
  }
  for (int k = d - 2; k < d; ++k) triangles_[star.slots[k]].v = {-1, -1, -1};
}

}  // namespace tinlod
