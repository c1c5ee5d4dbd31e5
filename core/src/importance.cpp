// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/importance.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>

#include "tinlod/error.h"
#include "triangle_contains.h"

namespace tinlod {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

K::Point_2 xy(const Point3& p) { return K::Point_2(p.x, p.y); }

bool leftTurn(const Point3& a, const Point3& b, const Point3& c) {
  return CGAL::orientation(xy(a), xy(b), xy(c)) == CGAL::LEFT_TURN;
}

// Power of p with respect to the circle through a, b, c (counter-clockwise): negative
// inside. From the in-circle determinant D and the orientation O, both relative to p:
// D = O (r^2 - |p - centre|^2).
double power(const Point3& p, const Point3& a, const Point3& b, const Point3& c) {
  const double ax = a.x - p.x, ay = a.y - p.y, bx = b.x - p.x, by = b.y - p.y, cx = c.x - p.x, cy = c.y - p.y;
  const double a2 = ax * ax + ay * ay, b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
  const double d = ax * (by * c2 - b2 * cy) - ay * (bx * c2 - b2 * cx) + a2 * (bx * cy - by * cx);
  const double o = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay);
  return -d / o;
}

double area2(const Point3& a, const Point3& b, const Point3& c) {
  return (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
}

double prismVolume(const Point3& a, const Point3& b, const Point3& c) {
  return 0.5 * area2(a, b, c) * (a.z + b.z + c.z) / 3.0;
}

// Height of the plane through a, b, c at (x, y).
double planeZ(const Point3& a, const Point3& b, const Point3& c, double x, double y) {
  const double d = area2(a, b, c);
  const double wb = ((x - a.x) * (c.y - a.y) - (c.x - a.x) * (y - a.y)) / d;
  const double wc = ((b.x - a.x) * (y - a.y) - (x - a.x) * (b.y - a.y)) / d;
  return a.z + wb * (b.z - a.z) + wc * (c.z - a.z);
}

bool contains(const Point3& a, const Point3& b, const Point3& c, const Point3& s) {
  return triangleContains(xy(a), xy(b), xy(c), xy(s));
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

// Devillers' ear queue over the ring as a cyclic list: each ear keeps its rank, and
// clipping one re-ranks only its two neighbours.
class EarClipper {
 public:
  explicit EarClipper(const Star& star) : star_(star), prev_(lists_.prev), next_(lists_.next), power_(lists_.power), convex_(lists_.convex) {
    const int d = static_cast<int>(star.ring.size());
    prev_.resize(d), next_.resize(d), power_.resize(d), convex_.resize(d);
    for (int i = 0; i < d; ++i) prev_[i] = (i + d - 1) % d, next_[i] = (i + 1) % d;
    for (int i = 0; i < d; ++i) rank(i);
  }

  // exact: confirm each ear with exact predicates, as the deletion needs; otherwise the
  // floating-point ranking alone, enough for an importance value.
  void run(std::vector<LocalTriangle>& out, bool exact) {
    out.clear();
    int head = 0;
    for (int m = static_cast<int>(star_.ring.size()); m > 3; --m) {
      int ear = bestEar(head, m);
      if (exact && (ear < 0 || !delaunay(ear))) ear = firstDelaunayEar(head, m);
      if (ear < 0) return;  // no convex ear: not a star polygon (cannot happen for a star)
      out.push_back({prev_[ear], ear, next_[ear]});
      next_[prev_[ear]] = next_[ear], prev_[next_[ear]] = prev_[ear];
      if (head == ear) head = next_[ear];
      rank(prev_[ear]), rank(next_[ear]);
    }
    if (star_.ring.size() >= 3) out.push_back({head, next_[head], next_[next_[head]]});
  }

 private:
  void rank(int i) {
    const std::vector<Point3>& ring = star_.ring;
    convex_[i] = leftTurn(ring[prev_[i]], ring[i], ring[next_[i]]);
    if (convex_[i]) power_[i] = power(star_.centre, ring[prev_[i]], ring[i], ring[next_[i]]);
  }

  int bestEar(int head, int m) const {
    int best = -1;
    for (int i = head, k = 0; k < m; ++k, i = next_[i])
      if (convex_[i] && (best < 0 || power_[i] > power_[best])) best = i;
    return best;
  }

  // Convex, and no other vertex of the polygon strictly inside its circumcircle: a
  // triangle of the polygon's Delaunay triangulation (exact predicates).
  bool delaunay(int i) const {
    if (!convex_[i]) return false;
    const std::vector<Point3>& ring = star_.ring;
    const K::Point_2 a = xy(ring[prev_[i]]), b = xy(ring[i]), c = xy(ring[next_[i]]);
    for (int j = next_[next_[i]]; j != prev_[i]; j = next_[j])
      if (CGAL::side_of_oriented_circle(a, b, c, xy(ring[j])) == CGAL::ON_POSITIVE_SIDE) return false;
    return true;
  }

  // Only in a near tie, where the floating-point ranking chose an ear the exact test
  // refuses.
  int firstDelaunayEar(int head, int m) const {
    for (int i = head, k = 0; k < m; ++k, i = next_[i])
      if (delaunay(i)) return i;
    throw Error("internal error: a star polygon has no Delaunay ear");
  }

  // Kept per thread: the simplifier clips millions of small stars.
  struct Lists {
    std::vector<int> prev, next;
    std::vector<double> power;
    std::vector<char> convex;
  };
  static thread_local Lists lists_;
  const Star& star_;
  std::vector<int>&prev_, &next_;
  std::vector<double>& power_;
  std::vector<char>& convex_;
};

thread_local EarClipper::Lists EarClipper::lists_;

}  // namespace

void retriangulateStar(const Star& star, std::vector<LocalTriangle>& out) { EarClipper(star).run(out, true); }

namespace {

const std::vector<LocalTriangle>& retriangulateInScratch(const Star& star, bool exact) {
  thread_local std::vector<LocalTriangle> out;
  EarClipper(star).run(out, exact);
  return out;
}

}  // namespace

std::vector<LocalTriangle> retriangulateStar(const Star& star) {
  std::vector<LocalTriangle> out;
  retriangulateStar(star, out);
  return out;
}

double volumeChange(const Star& star, const std::vector<LocalTriangle>& without) {
  double with = 0, after = 0;
  const std::size_t n = star.ring.size();
  for (std::size_t i = 0; i < n; ++i) with += prismVolume(star.centre, star.ring[i], star.ring[(i + 1) % n]);
  for (const LocalTriangle& t : without) after += prismVolume(star.ring[t[0]], star.ring[t[1]], star.ring[t[2]]);
  return std::fabs(with - after);
}

double normalFlatness(const Star& star) {
  const std::size_t n = star.ring.size();
  std::vector<std::array<double, 3>> normals;
  double mx = 0, my = 0, mz = 0;
  for (std::size_t i = 0; i < n; ++i) {
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

int triangleHolding(const Star& star, const LocalTriangle* tris, std::size_t count, const Point3& p) {
  for (std::size_t j = 0; j < count; ++j)
    if (contains(star.ring[tris[j][0]], star.ring[tris[j][1]], star.ring[tris[j][2]], p)) return static_cast<int>(j);
  return -1;
}

double verticalDistance(const Star& star, const LocalTriangle& t, const Point3& p) {
  const Point3 &a = star.ring[t[0]], &b = star.ring[t[1]], &c = star.ring[t[2]];
  return std::fabs(p.z - planeZ(a, b, c, p.x, p.y));
}

double maxVerticalError(const Star& star, const std::vector<LocalTriangle>& without,
                        const std::vector<Point3>& samples) {
  double worst = 0;
  auto measure = [&](const Point3& s) {
    const int j = triangleHolding(star, without.data(), without.size(), s);
    if (j >= 0) worst = std::max(worst, verticalDistance(star, without[j], s));
  };
  measure(star.centre);
  for (const Point3& s : samples) measure(s);
  return worst;
}

double importance(Measure measure, const Star& star, const std::vector<Point3>& samples) {
  switch (measure) {
    case Measure::Degree: return static_cast<double>(star.ring.size());
    case Measure::Normal: return 1.0 - normalFlatness(star);
    case Measure::Volume: return volumeChange(star, retriangulateInScratch(star, false));
    // Exact, as the deletion's: the error is then the one the deletion certifies.
    case Measure::Error: return maxVerticalError(star, retriangulateInScratch(star, true), samples);
  }
  return 0;
}

}  // namespace tinlod
