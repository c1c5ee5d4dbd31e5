// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/importance.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>

#include <cmath>
#include <limits>

#include "tinlod/error.h"

namespace tinlod {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

K::Point_2 xy(const Point3& p) { return K::Point_2(p.x, p.y); }

bool leftTurn(const Point3& a, const Point3& b, const Point3& c) {
  return CGAL::orientation(xy(a), xy(b), xy(c)) == CGAL::LEFT_TURN;
}

struct Relative {
  double x, y, r2;  // x, y relative to the star's centre, and x^2 + y^2
};

// CGAL's floating-point kernel, for the importance's ranking only: it decides no part of
// any TIN, and its orientation costs a third of what the exact kernel's filtered one does.
// Taken on the coordinates relative to the centre, as power() is: its determinant is
// power()'s O term, formula for formula, so the compiler works it out once for both
// (a tenth fewer instructions in the volume importance).
using FloatKernel = CGAL::Simple_cartesian<double>;

bool leftTurnInFloat(const Relative& a, const Relative& b, const Relative& c) {
  return CGAL::orientation(FloatKernel::Point_2(a.x, a.y), FloatKernel::Point_2(b.x, b.y),
                           FloatKernel::Point_2(c.x, c.y)) == CGAL::LEFT_TURN;
}

// Power of the centre (the origin of the relative coordinates) with respect to the circle
// through a, b, c (counter-clockwise): negative inside. From the in-circle determinant D
// and the orientation O, both relative to the centre: D = O (r^2 - |centre - m|^2).
double power(const Relative& a, const Relative& b, const Relative& c) {
  const double d = a.x * (b.y * c.r2 - b.r2 * c.y) - a.y * (b.x * c.r2 - b.r2 * c.x) + a.r2 * (b.x * c.y - b.y * c.x);
  const double o = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
  return -d / o;
}

double area2(const Point3& a, const Point3& b, const Point3& c) {
  return (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
}

double prismVolume(const Point3& a, const Point3& b, const Point3& c) {
  return 0.5 * area2(a, b, c) * (a.z + b.z + c.z) / 3.0;
}

}  // namespace

std::string measureName(Measure measure) {
  switch (measure) {
    case Measure::Degree: return "degree";
    case Measure::Volume: return "volume";
    case Measure::Normal: return "normal";
    case Measure::Error: return "error";
  }
  return "?";
}

Measure parseMeasure(const std::string& name) {
  for (Measure m : {Measure::Degree, Measure::Volume, Measure::Normal, Measure::Error})
    if (measureName(m) == name) return m;
  throw Error("unknown method '" + name + "': choose degree, volume, normal or error");
}

namespace {

// The ear queue's lists: on the stack for the usual small star, per thread beyond.
struct EarLists {
  int* prev;
  int* next;
  double* power;
  Relative* rel;
};

// Devillers' ear queue over the ring as a cyclic list: each ear keeps its rank, and
// clipping one re-ranks only its two neighbours.
class EarClipper {
 public:
  EarClipper(const Star& star, const EarLists& lists, bool exact) : star_(star), l_(lists), exact_(exact) {
    const int d = static_cast<int>(star.ring.size());
    for (int i = 0; i < d; ++i) {
      const double x = star.ring[i].x - star.centre.x, y = star.ring[i].y - star.centre.y;
      l_.rel[i] = {x, y, x * x + y * y};
      l_.prev[i] = i == 0 ? d - 1 : i - 1, l_.next[i] = i + 1 == d ? 0 : i + 1;
    }
    for (int i = 0; i < d; ++i) rank(i);
  }

  // Calls emit(triangle) for each of the d - 2 triangles. exact: convexity by exact
  // orientation and each ear confirmed with exact predicates, as the deletion needs;
  // otherwise floating point throughout, enough for an importance value.
  template <class Emit>
  void run(Emit emit) {
    int* prev = l_.prev;
    int* next = l_.next;
    int head = 0;
    for (int m = static_cast<int>(star_.ring.size()); m > 3; --m) {
      int ear = bestEar();
      if (exact_ && (ear < 0 || !delaunay(ear))) ear = firstDelaunayEar(head, m);
      if (ear < 0) return;  // no convex ear: not a star polygon (cannot happen for a star)
      emit(LocalTriangle{prev[ear], ear, next[ear]});
      next[prev[ear]] = next[ear], prev[next[ear]] = prev[ear];
      l_.power[ear] = -std::numeric_limits<double>::infinity();  // clipped: never the best again
      if (head == ear) head = next[ear];
      rank(prev[ear]), rank(next[ear]);
    }
    if (star_.ring.size() >= 3) emit(LocalTriangle{head, next[head], next[next[head]]});
  }

 private:
  // A reflex vertex ranks below every convex one (whose power, in a degenerate
  // floating-point case, is clamped above it), so it is never the best ear.
  void rank(int i) {
    const std::vector<Point3>& ring = star_.ring;
    const int p = l_.prev[i], n = l_.next[i];
    constexpr double lowest = -std::numeric_limits<double>::max();
    if (!(exact_ ? leftTurn(ring[p], ring[i], ring[n]) : leftTurnInFloat(l_.rel[p], l_.rel[i], l_.rel[n]))) {
      l_.power[i] = -std::numeric_limits<double>::infinity();
      return;
    }
    const double pw = power(l_.rel[p], l_.rel[i], l_.rel[n]);
    l_.power[i] = pw > lowest ? pw : lowest;
  }
  bool convex(int i) const { return l_.power[i] != -std::numeric_limits<double>::infinity(); }

  // The head is always the smallest index left, so the list from the head runs in index
  // order: a scan of the whole array, clipped ears ranked lowest, picks the same ear
  // without following the links. Written without a branch in the loop, where the
  // comparisons' mispredictions cost a quarter of the volume importance's time.
  int bestEar() const {
    const int d = static_cast<int>(star_.ring.size());
    int best = 0;
    double top = l_.power[0];
    for (int i = 1; i < d; ++i) {
      const bool higher = l_.power[i] > top;
      top = higher ? l_.power[i] : top;
      best = higher ? i : best;
    }
    return convex(best) ? best : -1;
  }

  // Convex, and no other vertex of the polygon strictly inside its circumcircle: a
  // triangle of the polygon's Delaunay triangulation (exact predicates).
  bool delaunay(int i) const {
    if (!convex(i)) return false;
    const std::vector<Point3>& ring = star_.ring;
    const K::Point_2 a = xy(ring[l_.prev[i]]), b = xy(ring[i]), c = xy(ring[l_.next[i]]);
    for (int j = l_.next[l_.next[i]]; j != l_.prev[i]; j = l_.next[j])
      if (CGAL::side_of_oriented_circle(a, b, c, xy(ring[j])) == CGAL::ON_POSITIVE_SIDE) return false;
    return true;
  }

  // Only in a near tie, where the floating-point ranking chose an ear the exact test
  // refuses.
  int firstDelaunayEar(int head, int m) const {
    for (int i = head, k = 0; k < m; ++k, i = l_.next[i])
      if (delaunay(i)) return i;
    throw Error("internal error: a star polygon has no Delaunay ear");
  }

  const Star& star_;
  EarLists l_;
  bool exact_;
};

// Runs the ear queue with lists on the stack for stars of up to kStackEars vertices,
// which is nearly all: the simplifier clips millions of them.
template <class Emit>
void clipEars(const Star& star, bool exact, Emit emit) {
  constexpr std::size_t kStackEars = 32;
  const std::size_t d = star.ring.size();
  if (d <= kStackEars) {
    int prev[kStackEars], next[kStackEars];
    double power[kStackEars];
    Relative rel[kStackEars];
    EarClipper(star, {prev, next, power, rel}, exact).run(emit);
    return;
  }
  thread_local std::vector<int> prev, next;
  thread_local std::vector<double> power;
  thread_local std::vector<Relative> rel;
  prev.resize(d), next.resize(d), power.resize(d), rel.resize(d);
  EarClipper(star, {prev.data(), next.data(), power.data(), rel.data()}, exact).run(emit);
}

}  // namespace

bool retriangulateStar(const Star& star, std::vector<LocalTriangle>& out) {
  if (star.open) return retriangulateOpenStar(star, out);
  out.clear();
  clipEars(star, true, [&](const LocalTriangle& t) { out.push_back(t); });
  return true;
}

std::vector<LocalTriangle> retriangulateStar(const Star& star) {
  std::vector<LocalTriangle> out;
  retriangulateStar(star, out);
  return out;
}

void ringEdgeTriangles(const LocalTriangle* fill, int d, int* onEdge) {
  for (int j = 0; j + 2 < d; ++j)
    for (int e = 0; e < 3; ++e)
      if (fill[j][(e + 1) % 3] == (fill[j][e] + 1) % d) onEdge[fill[j][e]] = j;
}

namespace {

// The volume under the star with its centre; for an open star, less the prism under the
// vertex and its two outline neighbours (see volumeChange).
double coneVolume(const Star& star) {
  double with = 0;
  const std::size_t n = star.ring.size();
  for (std::size_t i = 0; i + 1 < n; ++i) with += prismVolume(star.centre, star.ring[i], star.ring[i + 1]);
  if (!star.open) return with + prismVolume(star.centre, star.ring[n - 1], star.ring[0]);
  return with - prismVolume(star.centre, star.ring[0], star.ring[n - 1]);
}

// volumeChange on the floating-point ranking, summed as the ears are clipped.
double volumeChangeRanked(const Star& star) {
  double after = 0;
  clipEars(star, false, [&](const LocalTriangle& t) { after += prismVolume(star.ring[t[0]], star.ring[t[1]], star.ring[t[2]]); });
  return std::fabs(coneVolume(star) - after);
}

double openVolumeChange(const Star& star) {
  thread_local std::vector<LocalTriangle> fill;
  if (!retriangulateOpenStar(star, fill)) return std::numeric_limits<double>::infinity();
  return volumeChange(star, fill);
}

}  // namespace

double volumeChange(const Star& star, const std::vector<LocalTriangle>& without) {
  double after = 0;
  for (const LocalTriangle& t : without) after += prismVolume(star.ring[t[0]], star.ring[t[1]], star.ring[t[2]]);
  return std::fabs(coneVolume(star) - after);
}

double normalFlatness(const Star& star) {
  const std::size_t n = star.ring.size();
  const std::size_t triangles = star.open ? n - 1 : n;
  std::vector<std::array<double, 3>> normals;
  double mx = 0, my = 0, mz = 0;
  for (std::size_t i = 0; i < triangles; ++i) {
    const Point3 &p = star.centre, &a = star.ring[i], &b = star.ring[(i + 1) % n];
    const double ux = a.x - p.x, uy = a.y - p.y, uz = a.z - p.z, vx = b.x - p.x, vy = b.y - p.y, vz = b.z - p.z;
    std::array<double, 3> nrm{uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
    const double len = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    if (len == 0) continue;
    for (double& c : nrm) c /= len;
    mx += nrm[0], my += nrm[1], mz += nrm[2];
    normals.push_back(nrm);
  }
  const double mlen = std::sqrt(mx * mx + my * my + mz * mz);
  if (normals.empty() || mlen == 0) return 0;
  double sum = 0;
  for (const auto& nrm : normals) sum += (nrm[0] * mx + nrm[1] * my + nrm[2] * mz) / mlen;
  return sum / normals.size();
}

bool strictlyInCircle(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return CGAL::side_of_oriented_circle(xy(a), xy(b), xy(c), xy(d)) == CGAL::ON_POSITIVE_SIDE;
}

double importance(Measure measure, const Star& star) {
  switch (measure) {
    case Measure::Degree: return static_cast<double>(star.ring.size());
    case Measure::Normal: return 1.0 - normalFlatness(star);
    case Measure::Volume: return star.open ? openVolumeChange(star) : volumeChangeRanked(star);
    case Measure::Error: break;  // the simplifier's, against the DEM
  }
  return 0;
}

}  // namespace tinlod
