// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/douglas_peucker.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <utility>

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

// Segments bucketed by a uniform grid of about one cell per segment.
class SegmentGrid {
 public:
  explicit SegmentGrid(const std::vector<Segment>& segments) {
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (const Segment& g : segments) {
      const auto box = g.s.bbox();
      x0 = std::min(x0, box.xmin()), y0 = std::min(y0, box.ymin()), x1 = std::max(x1, box.xmax()), y1 = std::max(y1, box.ymax());
    }
    origin_ = {x0, y0};
    // About one segment a cell; on a thin extent (all lines vertical, say) the area says
    // nothing, and the longer side spreads them instead.
    const double n = double(std::max<std::size_t>(1, segments.size()));
    const double side = std::max(std::sqrt((x1 - x0) * (y1 - y0) / n), std::max(x1 - x0, y1 - y0) / n);
    cell_ = side > 0 ? side : 1;
    for (std::size_t i = 0; i < segments.size(); ++i) {
      const auto box = segments[i].s.bbox();
      for (long cx = key(box.xmin(), 0); cx <= key(box.xmax(), 0); ++cx)
        for (long cy = key(box.ymin(), 1); cy <= key(box.ymax(), 1); ++cy) cells_[{cx, cy}].push_back(i);
    }
  }
  template <class Visit>
  void eachCell(Visit visit) const {
    for (const auto& [k, members] : cells_) visit(members);
  }

 private:
  struct Hash {
    std::size_t operator()(const std::pair<long, long>& k) const { return std::hash<long>()(k.first * 73856093L ^ k.second); }
  };
  long key(double v, int axis) const { return static_cast<long>(std::floor((v - origin_[axis]) / cell_)); }
  std::array<double, 2> origin_{};
  double cell_ = 1;
  std::unordered_map<std::pair<long, long>, std::vector<std::size_t>, Hash> cells_;
};

}  // namespace

std::size_t crossingCount(const std::vector<Polyline>& lines) {
  std::vector<Segment> segments;
  for (std::size_t l = 0; l < lines.size(); ++l)
    for (std::size_t i = 0; i + 1 < lines[l].size(); ++i)
      segments.push_back({l, Kernel::Segment_2({lines[l][i][0], lines[l][i][1]}, {lines[l][i + 1][0], lines[l][i + 1][1]})});
  if (segments.empty()) return 0;
  // A pair sharing several cells is counted once: a set of the pairs found.
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  SegmentGrid(segments).eachCell([&](const std::vector<std::size_t>& members) {
    for (std::size_t i = 0; i < members.size(); ++i)
      for (std::size_t j = i + 1; j < members.size(); ++j) {
        const Segment &a = segments[members[i]], &b = segments[members[j]];
        if (a.line != b.line && CGAL::do_intersect(a.s, b.s)) pairs.push_back(std::minmax(members[i], members[j]));
      }
  });
  std::sort(pairs.begin(), pairs.end());
  return static_cast<std::size_t>(std::unique(pairs.begin(), pairs.end()) - pairs.begin());
}

}  // namespace tinlod
