// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/douglas_peucker.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "box_grid.h"

namespace tinlod {
namespace {

// Distance from p to the segment ab (to a when a and b coincide, as on a closed contour).
double segmentDistance(const LinePoint& p, const LinePoint& a, const LinePoint& b) {
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double length2 = dx * dx + dy * dy;
  double t = length2 > 0 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p[0] - (a[0] + t * dx), p[1] - (a[1] + t * dy));
}

}  // namespace

std::vector<double> douglasPeuckerValues(const Polyline& line) {
  const double infinity = std::numeric_limits<double>::infinity();
  std::vector<double> values(line.size(), infinity);
  if (line.size() < 3) return values;
  std::vector<std::pair<std::size_t, std::size_t>> stretches{{0, line.size() - 1}};
  if (line.front() == line.back()) {
    // A closed line has no chord: it is anchored at its start and the vertex farthest from
    // it too, so that no threshold shrinks it to a point.
    std::size_t far = 1;
    for (std::size_t i = 1; i + 1 < line.size(); ++i)
      if (segmentDistance(line[i], line[0], line[0]) > segmentDistance(line[far], line[0], line[0])) far = i;
    values[far] = infinity;
    stretches = {{0, far}, {far, line.size() - 1}};
  }
  while (!stretches.empty()) {
    const auto [a, b] = stretches.back();
    stretches.pop_back();
    if (b - a < 2) continue;
    std::size_t farthest = a + 1;
    double distance = -1;
    for (std::size_t i = a + 1; i < b; ++i) {
      const double d = segmentDistance(line[i], line[a], line[b]);
      if (d > distance) distance = d, farthest = i;
    }
    values[farthest] = std::min({distance, values[a], values[b]});
    stretches.push_back({a, farthest});
    stretches.push_back({farthest, b});
  }
  return values;
}

Polyline simplified(const Polyline& line, const std::vector<double>& values, double threshold) {
  Polyline out;
  for (std::size_t i = 0; i < line.size(); ++i)
    if (values[i] > threshold) out.push_back(line[i]);
  return out;
}

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

struct Segment {
  std::size_t line;
  Kernel::Segment_2 s;
};

}  // namespace

std::size_t crossingCount(const std::vector<Polyline>& lines) {
  std::vector<Segment> segments;
  for (std::size_t l = 0; l < lines.size(); ++l)
    for (std::size_t i = 0; i + 1 < lines[l].size(); ++i)
      segments.push_back({l, Kernel::Segment_2({lines[l][i][0], lines[l][i][1]}, {lines[l][i + 1][0], lines[l][i + 1][1]})});
  if (segments.empty()) return 0;
  std::vector<Box> boxes;
  for (const Segment& g : segments) boxes.push_back({g.s.bbox().xmin(), g.s.bbox().ymin(), g.s.bbox().xmax(), g.s.bbox().ymax()});
  // A pair sharing several buckets is counted once: a set of the pairs found.
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  BoxGrid(boxes).eachBucket([&](const std::uint32_t* first, const std::uint32_t* last) {
    for (const std::uint32_t* i = first; i != last; ++i)
      for (const std::uint32_t* j = i + 1; j != last; ++j) {
        const Segment &a = segments[*i], &b = segments[*j];
        if (a.line != b.line && CGAL::do_intersect(a.s, b.s)) pairs.push_back(std::minmax<std::size_t>(*i, *j));
      }
  });
  std::sort(pairs.begin(), pairs.end());
  return static_cast<std::size_t>(std::unique(pairs.begin(), pairs.end()) - pairs.begin());
}

}  // namespace tinlod
