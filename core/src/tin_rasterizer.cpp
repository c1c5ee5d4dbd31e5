// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/tin_rasterizer.h"

#include <algorithm>
#include <cmath>

#include "parallel_rows.h"

namespace tinlod {
namespace {

using Pos = std::array<double, 2>;

// A hair of tolerance so that points on an edge are never missed by both of its
// triangles through rounding; both then write the same height.
constexpr double kEdgeTolerance = 1e-9;

struct Plane {
  Pos a, b, c;
  double za, zb, zc, area;
};

double edge(const Pos& p, const Pos& q, double x, double y) { return (q[0] - p[0]) * (y - p[1]) - (q[1] - p[1]) * (x - p[0]); }

// Fills the points of rows [rowBegin, rowEnd) inside one triangle.
void fillTriangle(const Plane& t, int rowBegin, int rowEnd, Grid& out) {
  const double tol = kEdgeTolerance * std::fabs(t.area);
  const int r0 = std::max(rowBegin, static_cast<int>(std::ceil(std::min({t.a[1], t.b[1], t.c[1]}))));
  const int r1 = std::min(rowEnd - 1, static_cast<int>(std::floor(std::max({t.a[1], t.b[1], t.c[1]}))));
  const int c0 = std::max(0, static_cast<int>(std::ceil(std::min({t.a[0], t.b[0], t.c[0]}))));
  const int c1 = std::min(out.cols - 1, static_cast<int>(std::floor(std::max({t.a[0], t.b[0], t.c[0]}))));
  for (int r = r0; r <= r1; ++r)
    for (int c = c0; c <= c1; ++c) {
      const double wa = edge(t.b, t.c, c, r), wb = edge(t.c, t.a, c, r), wc = edge(t.a, t.b, c, r);
      const bool inside = t.area > 0 ? (wa >= -tol && wb >= -tol && wc >= -tol) : (wa <= tol && wb <= tol && wc <= tol);
      if (inside) out.at(c, r) = (wa * t.za + wb * t.zb + wc * t.zc) / t.area;
    }
}

}  // namespace

Grid rasterizeTin(const std::vector<Pos>& positions, const std::vector<double>& z, const std::vector<Triangle>& triangles,
                  int cols, int rows, const ProgressRange& progress) {
  Grid out(cols, rows);
  std::vector<Plane> planes;
  planes.reserve(triangles.size());
  for (const Triangle& t : triangles) {
    const Pos &a = positions[t[0]], &b = positions[t[1]], &c = positions[t[2]];
    const double area = edge(a, b, c[0], c[1]);
    if (area != 0) planes.push_back({a, b, c, z[t[0]], z[t[1]], z[t[2]], area});
  }
  // Triangles sorted by their lowest row let each band of rows skip to its own.
  std::sort(planes.begin(), planes.end(), [](const Plane& p, const Plane& q) {
    return std::min({p.a[1], p.b[1], p.c[1]}) < std::min({q.a[1], q.b[1], q.c[1]});
  });
  double tallest = 0;
  for (const Plane& p : planes)
    tallest = std::max(tallest, std::max({p.a[1], p.b[1], p.c[1]}) - std::min({p.a[1], p.b[1], p.c[1]}));
  auto work = [&](int rowBegin, int rowEnd) {
    auto first = std::lower_bound(planes.begin(), planes.end(), rowBegin - tallest - 1, [](const Plane& p, double y) {
      return std::min({p.a[1], p.b[1], p.c[1]}) < y;
    });
    for (auto it = first; it != planes.end() && std::min({it->a[1], it->b[1], it->c[1]}) < rowEnd; ++it)
      fillTriangle(*it, rowBegin, rowEnd, out);
  };
  forRowBlocks(rows, work, [&](double f) { progress.report(f, "Interpolating the TIN"); });
  return out;
}

}  // namespace tinlod
