// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/concavity.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tinlod {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = 3.14159265358979323846;
constexpr double kShortestSecant = 0.1;  // of the window: shorter, the secant measure is undefined

double cross(const LinePoint& a, const LinePoint& b) { return a[0] * b[1] - a[1] * b[0]; }

// The line moved next to the origin: shoelace sums of far-away coordinates cancel badly.
Polyline centred(const Polyline& line) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const LinePoint& p : line) x0 = std::min(x0, p[0]), y0 = std::min(y0, p[1]), x1 = std::max(x1, p[0]), y1 = std::max(y1, p[1]);
  Polyline out(line);
  for (LinePoint& p : out) p = {p[0] - (x0 + x1) / 2, p[1] - (y0 + y1) / 2};
  return out;
}

LinePoint along(const LinePoint& a, const LinePoint& b, double t) { return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])}; }


std::vector<double> secantOpen(const Polyline& input, double window) {
  const std::size_t n = input.size();
  std::vector<double> out(n, kNaN);
  if (n < 3 || !(window > 0)) return out;
  const Polyline line = centred(input);
  std::vector<double> s(n, 0), shoelace(n, 0);  // arc length and prefix sums of cross products
  for (std::size_t i = 1; i < n; ++i) {
    s[i] = s[i - 1] + std::hypot(line[i][0] - line[i - 1][0], line[i][1] - line[i - 1][1]);
    shoelace[i] = shoelace[i - 1] + cross(line[i - 1], line[i]);
  }
  // The window's ends move forward with the vertex: segments lo and hi hold them.
  std::size_t lo = 0, hi = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (s[i] - window < 0 || s[i] + window > s[n - 1]) continue;
    while (s[lo + 1] < s[i] - window) ++lo;
    while (hi + 1 < n - 1 && s[hi + 1] < s[i] + window) ++hi;
    const LinePoint tail = along(line[lo], line[lo + 1], (s[i] - window - s[lo]) / std::max(s[lo + 1] - s[lo], 1e-300));
    const LinePoint head = along(line[hi], line[hi + 1], (s[i] + window - s[hi]) / std::max(s[hi + 1] - s[hi], 1e-300));
    // The closed section tail, vertices lo+1 .. hi, head, back to tail.
    const double twice = cross(tail, line[lo + 1]) + (shoelace[hi] - shoelace[lo + 1]) + cross(line[hi], head) + cross(head, tail);
    const double secant2 = (head[0] - tail[0]) * (head[0] - tail[0]) + (head[1] - tail[1]) * (head[1] - tail[1]);
    // A clockwise section bulges to the left: convex seen from the left, positive. Where
    // the line turns back on itself the secant shrinks and area over its square grows
    // without bound (2.9e10 on a contour whose ends came 0.5 mm apart): no measure there;
    // at a tenth of the window, a near-full circle gives the most, about 35.
    out[i] = secant2 >= kShortestSecant * kShortestSecant * window * window ? -0.5 * twice / secant2 : kNaN;
  }
  return out;
}


// Where the segment from a (inside the disk) to b leaves the circle of `radius` around p,
// or false when b is inside too.
bool leaves(const LinePoint& p, double radius, const LinePoint& a, const LinePoint& b, LinePoint& exit) {
  const double bx = b[0] - p[0], by = b[1] - p[1];
  if (bx * bx + by * by <= radius * radius) return false;
  const double ax = a[0] - p[0], ay = a[1] - p[1], dx = bx - ax, dy = by - ay;
  const double qa = dx * dx + dy * dy, qb = 2 * (ax * dx + ay * dy), qc = ax * ax + ay * ay - radius * radius;
  const double t = (-qb + std::sqrt(std::max(0.0, qb * qb - 4 * qa * qc))) / (2 * qa);
  exit = along(a, b, std::clamp(t, 0.0, 1.0));
  return true;
}

double diskAt(const Polyline& line, std::size_t i, double radius) {
  const LinePoint& p = line[i];
  Polyline section;  // built backwards from p to the entry, then turned
  LinePoint entry, exit;
  std::size_t k = i;
  for (;; --k) {  // backwards to where the line enters the disk
    if (k == 0) return kNaN;
    if (leaves(p, radius, line[k], line[k - 1], entry)) break;
    section.push_back(line[k - 1]);
  }
  section.push_back(entry);
  std::reverse(section.begin(), section.end());
  section.push_back(p);
  for (k = i;; ++k) {  // forwards to where it leaves
    if (k + 1 == line.size()) return kNaN;
    if (leaves(p, radius, line[k], line[k + 1], exit)) break;
    section.push_back(line[k + 1]);
  }
  section.push_back(exit);
  // The left part: the section, then the circle counter-clockwise from exit to entry.
  // Its area is the section closed by the chord, plus the circular segment the chord cuts.
  double twice = 0;
  for (std::size_t m = 0; m < section.size(); ++m) {
    const LinePoint a{section[m][0] - p[0], section[m][1] - p[1]};
    const LinePoint b{section[(m + 1) % section.size()][0] - p[0], section[(m + 1) % section.size()][1] - p[1]};
    twice += cross(a, b);
  }
  double alpha = std::atan2(entry[1] - p[1], entry[0] - p[0]) - std::atan2(exit[1] - p[1], exit[0] - p[0]);
  if (alpha < 0) alpha += 2 * kPi;
  const double left = 0.5 * twice + 0.5 * radius * radius * (alpha - std::sin(alpha));
  return 2 * left / (kPi * radius * radius) - 1;
}

std::vector<double> diskOpen(const Polyline& line, double radius) {
  std::vector<double> out(line.size(), kNaN);
  if (!(radius > 0)) return out;
  for (std::size_t i = 0; i < line.size(); ++i) out[i] = diskAt(line, i, radius);
  return out;
}

bool isRing(const Polyline& line) { return line.size() >= 4 && line.front() == line.back(); }

// A closed contour has no ends: it is measured on three laps of itself, the middle one
// kept, so that its start is measured as any other vertex.
template <class Measure>
std::vector<double> onRing(const Polyline& ring, double size, Measure measure) {
  double perimeter = 0;
  for (std::size_t i = 1; i < ring.size(); ++i) perimeter += std::hypot(ring[i][0] - ring[i - 1][0], ring[i][1] - ring[i - 1][1]);
  // A window reaching round the ring to itself measures nothing.
  if (2 * size >= perimeter) return std::vector<double>(ring.size(), kNaN);
  Polyline laps(ring);
  for (int lap = 0; lap < 2; ++lap) laps.insert(laps.end(), ring.begin() + 1, ring.end());
  const std::vector<double> all = measure(laps, size);
  std::vector<double> out(all.begin() + long(ring.size() - 1), all.begin() + long(2 * ring.size() - 1));
  return out;
}

}  // namespace

std::vector<double> secantConcavity(const Polyline& line, double window) {
  return isRing(line) ? onRing(line, window, secantOpen) : secantOpen(line, window);
}

std::vector<double> diskConcavity(const Polyline& line, double radius) {
  return isRing(line) ? onRing(line, radius, diskOpen) : diskOpen(line, radius);
}

std::string curvatureName(Curvature c) {
  return c == Curvature::Convex ? "convex" : c == Curvature::Concave ? "concave" : "straight";
}

std::vector<LinePart> curvatureParts(const Polyline& line, const std::vector<double>& secant, double threshold) {
  std::vector<LinePart> parts;
  if (line.size() < 2) return parts;
  std::vector<Curvature> cls(line.size(), Curvature::Straight);
  bool any = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (std::isnan(secant[i])) continue;
    cls[i] = secant[i] > threshold ? Curvature::Convex : secant[i] < -threshold ? Curvature::Concave : Curvature::Straight;
    any = true;
  }
  if (!any) return {{line, Curvature::Straight}};
  // Vertices without a value (near the ends) take their nearest valued neighbour's class.
  std::size_t first = 0;
  while (std::isnan(secant[first])) ++first;
  for (std::size_t i = 0; i < first; ++i) cls[i] = cls[first];
  for (std::size_t i = first + 1; i < line.size(); ++i)
    if (std::isnan(secant[i])) cls[i] = cls[i - 1];
  std::size_t start = 0;
  for (std::size_t i = 1; i <= line.size(); ++i)
    if (i == line.size() || cls[i] != cls[start]) {
      const std::size_t end = std::min(i, line.size() - 1);  // parts share their end vertices
      parts.push_back({Polyline(line.begin() + long(start), line.begin() + long(end) + 1), cls[start]});
      start = i;
    }
  return parts;
}

}  // namespace tinlod
