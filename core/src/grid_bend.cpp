// SPDX-License-Identifier: GPL-3.0-or-later
#include "grid_bend.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <mutex>
#include <vector>

#include "parallel_blocks.h"
#include "text_and_paths.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

// A vertex's place on the grid, in cells (its jitter included).
double gridCol(const TinVertex& v) { return v.col + 0.5 + double(v.dcol); }
double gridRow(const TinVertex& v) { return v.row + 0.5 + double(v.drow); }

// A triangle's centre on the grid, in cells: {column, row}.
std::array<double, 2> gridCentre(const TinVertex& a, const TinVertex& b, const TinVertex& c) {
  return {(gridCol(a) + gridCol(b) + gridCol(c)) / 3, (gridRow(a) + gridRow(b) + gridRow(c)) / 3};
}

double cross(double ax, double ay, double bx, double by, double cx, double cy) {
  return (bx - ax) * (cy - ay) - (cx - ax) * (by - ay);
}

// Twice the area over the longest side squared: about 1.7 for an equilateral triangle, near 0
// for a sliver, whose orientation the slightest bend may turn (2 slivers along vancouver's
// shore at 49 N) without overlapping anything measurable.
double fatness(double twiceArea, double ax, double ay, double bx, double by, double cx, double cy) {
  const auto squared = [](double dx, double dy) { return dx * dx + dy * dy; };
  const double longest = std::max({squared(bx - ax, by - ay), squared(cx - bx, cy - by), squared(ax - cx, ay - cy)});
  return longest > 0 ? std::fabs(twiceArea) / longest : 0;
}

constexpr double kSliver = 1e-3;

// The Frobenius norm of the map's second derivative (both coordinates) at a lattice point, from
// the nine points about it in `x`, `y` (row by row, -h to +h), `hc` and `hr` cells apart.
double secondDerivativeNorm(const double* x, const double* y, double hc, double hr) {
  double sum = 0;
  for (const double* f : {x, y}) {
    const double cc = (f[3] - 2 * f[4] + f[5]) / (hc * hc), rr = (f[1] - 2 * f[4] + f[7]) / (hr * hr);
    const double cr = (f[8] - f[6] - f[2] + f[0]) / (4 * hc * hr);
    sum += cc * cc + 2 * cr * cr + rr * rr;
  }
  return std::sqrt(sum);
}

}  // namespace

double bendBound(const Dem& dem, const CrsTransform& toTin) {
  if (toTin.isIdentity()) return 0;
  constexpr int kLattice = 32;
  const double hc = 0.5 * dem.width / kLattice, hr = 0.5 * dem.height / kLattice;
  std::vector<double> x, y;
  for (int j = 0; j < kLattice; ++j)
    for (int i = 0; i < kLattice; ++i)
      for (int dr = -1; dr <= 1; ++dr)
        for (int dc = -1; dc <= 1; ++dc) {
          const double col = (2 * i + 1 + dc) * hc, row = (2 * j + 1 + dr) * hr;
          x.push_back(dem.geotransform[0] + col * dem.geotransform[1]);
          y.push_back(dem.geotransform[3] + row * dem.geotransform[5]);
        }
  try {
    toTin.apply(x, y);
  } catch (const Error&) {
    return std::numeric_limits<double>::infinity();
  }
  std::vector<double> norm(kLattice * kLattice);
  for (std::size_t k = 0; k < norm.size(); ++k) norm[k] = secondDerivativeNorm(&x[9 * k], &y[9 * k], hc, hr);
  const double largest = *std::max_element(norm.begin(), norm.end());
  // A CRS that is the grid's up to rounding (ETRS89 / UTM to WGS 84 / UTM, a shift) has second
  // differences of noise, which jump from sample to sample: bounded by the noise itself.
  double extent = 0;
  for (std::size_t k = 0; k < x.size(); ++k) extent = std::max({extent, std::fabs(x[k]), std::fabs(y[k])});
  const double noise = 64 * std::numeric_limits<double>::epsilon() * extent / std::min(hc * hc, hr * hr);
  if (largest <= noise) return 2 * noise;
  for (int j = 0; j < kLattice; ++j)
    for (int i = 0; i < kLattice; ++i) {
      const double here = norm[j * kLattice + i];
      if ((i + 1 < kLattice && std::fabs(norm[j * kLattice + i + 1] - here) > largest / 2) ||
          (j + 1 < kLattice && std::fabs(norm[(j + 1) * kLattice + i] - here) > largest / 2) || !std::isfinite(here))
        return std::numeric_limits<double>::infinity();
    }
  return 2 * largest;
}

std::size_t foldedTriangles(const std::vector<TinVertex>& vertices, std::size_t count, const TriangleAt& triangle) {
  // +1 where the grid and the CRS agree on a triangle's turn, -1 where they do not, 0 for none;
  // a sliver on either side, turned by the slightest bend, says nothing of a fold when `sliver`
  // is the turn to weigh (the fewer, so that the many are not weighed).
  const auto turn = [&](std::size_t i, int sliver) {
    const Triangle& t = triangle(i);
    const TinVertex &a = vertices[t[0]], &b = vertices[t[1]], &c = vertices[t[2]];
    const double grid = cross(gridCol(a), gridRow(a), gridCol(b), gridRow(b), gridCol(c), gridRow(c));
    const double map = cross(a.x, a.y, b.x, b.y, c.x, c.y);
    if (grid == 0 || map == 0) return 0;
    const int agree = (grid > 0) == (map > 0) ? 1 : -1;
    if (agree == sliver &&
        (fatness(grid, gridCol(a), gridRow(a), gridCol(b), gridRow(b), gridCol(c), gridRow(c)) < kSliver ||
         fatness(map, a.x, a.y, b.x, b.y, c.x, c.y) < kSliver))
      return 0;
    return agree;
  };
  // Summed over every core: a fine insert TIN has millions of triangles.
  const auto sum = [&](const std::function<std::int64_t(std::size_t)>& term) {
    std::atomic<std::int64_t> total{0};
    forEachBlock(static_cast<int>(count), [&](int begin, int end) {
      std::int64_t part = 0;
      for (int i = begin; i < end; ++i) part += term(std::size_t(i));
      total += part;
    }, {});
    return total.load();
  };
  // A north-up grid's rows run south, so most triangles turn: the fewer are the folded.
  const int folded = sum([&](std::size_t i) { return turn(i, 0); }) >= 0 ? -1 : 1;
  return std::size_t(sum([&](std::size_t i) { return turn(i, folded) == folded ? 1 : 0; }));
}

// The centre lands within `bend` / 2 times the corners' mean squared distance from it (in cells)
// of the corners' mean in the CRS (Taylor), and the triangle's plane there climbs by its
// gradient times that.
double heightGapBound(const TinVertex& a, const TinVertex& b, const TinVertex& c, double bend) {
  const auto [col, row] = gridCentre(a, b, c);
  double spread = 0;
  for (const TinVertex* v : {&a, &b, &c}) {
    const double dc = gridCol(*v) - col, dr = gridRow(*v) - row;
    spread += dc * dc + dr * dr;
  }
  // The plane's normal in the CRS: its gradient is (nx, ny) / |nz|.
  const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
  const double vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
  const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
  if (nz == 0) return std::numeric_limits<double>::infinity();
  return std::sqrt(nx * nx + ny * ny) / std::fabs(nz) * bend / 2 * spread / 3;
}

HeightGap heightGap(const Dem& dem, const CrsTransform& toTin, const std::vector<TinVertex>& vertices, std::size_t count,
                    const TriangleAt& triangle, double floor) {
  HeightGap out;
  if (toTin.isIdentity()) return out;
  const double bend = bendBound(dem, toTin);
  // The triangles to measure, picked on every core; PROJ then takes them on one.
  std::vector<std::uint32_t> picked;
  std::mutex pickedMutex;
  forEachBlock(static_cast<int>(count), [&](int begin, int end) {
    std::vector<std::uint32_t> part;
    for (int i = begin; i < end; ++i) {
      const Triangle& t = triangle(std::size_t(i));
      const TinVertex &a = vertices[t[0]], &b = vertices[t[1]], &c = vertices[t[2]];
      if (!(heightGapBound(a, b, c, bend) > floor)) continue;
      // Only centres over data: across a void no DEM cell tells the two readings apart.
      const auto [col, row] = gridCentre(a, b, c);
      if (dem.valid(static_cast<int>(std::floor(row)), static_cast<int>(std::floor(col)))) part.push_back(std::uint32_t(i));
    }
    const std::lock_guard<std::mutex> lock(pickedMutex);
    picked.insert(picked.end(), part.begin(), part.end());
  }, {});
  std::sort(picked.begin(), picked.end());  // in the triangles' order, whatever the threads' timing
  // A chunk at a time: a fine TIN's centres would take a copy of its size; a chunk PROJ cannot
  // take (its reason is the run's error where it matters) is passed over.
  constexpr std::size_t kChunk = 1 << 16;
  std::vector<double> x, y;
  for (std::size_t start = 0; start < picked.size(); start += kChunk) {
    const std::size_t end = std::min(picked.size(), start + kChunk);
    x.clear(), y.clear();
    for (std::size_t k = start; k < end; ++k) {
      const Triangle& t = triangle(picked[k]);
      const auto [col, row] = gridCentre(vertices[t[0]], vertices[t[1]], vertices[t[2]]);
      x.push_back(dem.geotransform[0] + col * dem.geotransform[1]);
      y.push_back(dem.geotransform[3] + row * dem.geotransform[5]);
    }
    try {
      toTin.apply(x, y);
    } catch (const Error&) {
      continue;
    }
    out.measured += end - start;
    for (std::size_t k = start; k < end; ++k) {
      const Triangle& t = triangle(picked[k]);
      const TinVertex &a = vertices[t[0]], &b = vertices[t[1]], &c = vertices[t[2]];
      const double area = cross(a.x, a.y, b.x, b.y, c.x, c.y);
      if (area == 0) continue;
      // The centre's barycentric weights in the TIN's CRS; on the grid they are a third each.
      const double px = x[k - start], py = y[k - start];
      const double wa = cross(px, py, b.x, b.y, c.x, c.y) / area, wb = cross(a.x, a.y, px, py, c.x, c.y) / area;
      out.metres = std::max(out.metres, std::fabs(wa * a.z + wb * b.z + (1 - wa - wb) * c.z - (a.z + b.z + c.z) / 3));
    }
  }
  return out;
}

void checkGridBend(const Dem& dem, const CrsTransform& toTin, const std::vector<TinVertex>& vertices, std::size_t turnCount,
                   const TriangleAt& turnAt, std::size_t gapCount, const TriangleAt& gapAt, double maxError,
                   const std::string& what, const ProgressRange& progress) {
  if (const std::size_t folded = foldedTriangles(vertices, turnCount, turnAt); folded > 0)
    throw Error("the TIN's CRS, " + toTin.targetName() + ", turns " + std::to_string(folded) +
                " of its triangles over against the DEM's grid, where tinlod measures them (a DEM that wraps the globe, or "
                "reaches a pole): warp the DEM to a projected CRS first (gdalwarp -t_srs), so that its grid is the "
                "TIN's plane, or cut it into regions");
  // A quarter of the largest error: swiss_alps' coarsest level parts by 84 m at one centre, 7 %
  // of its 1255 m, yet its RMSE read in the CRS is within 0.4 % of the grid's.
  const double tolerance = std::max(0.25 * maxError, 0.01);
  const double gap = heightGap(dem, toTin, vertices, gapCount, gapAt, tolerance).metres;
  if (!(gap > tolerance)) return;
  progress.warn("read in its CRS (" + toTin.targetName() + "), " + what + "'s triangles part by up to " +
                formatNumber(std::round(gap * 100) / 100) + " m at their centres from their heights on the DEM's grid, "
                "where tinlod measures its errors (at most " + formatNumber(std::round(maxError * 100) / 100) +
                " m): the CRS bends the grid (near a pole, or over a wide DEM); for figures that hold in the CRS, warp "
                "the DEM to it first (gdalwarp -t_srs)");
}

}  // namespace tinlod
