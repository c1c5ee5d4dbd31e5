// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <thread>
#include <vector>

#include "tinlod/bspline_surface.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

using Field = std::function<double(double x, double y)>;
using Rows = std::vector<std::vector<SurfacePoint>>;

// Test point (col, row) lies at x = col * cellWidth[row] east, y = -row * cellHeight north.
Grid sampled(int cols, int rows, const std::vector<double>& cellWidth, double cellHeight, const Field& f) {
  Grid g(cols, rows);
  for (int row = 0; row < rows; ++row)
    for (int col = 0; col < cols; ++col) g.at(col, row) = f(col * cellWidth[row], -row * cellHeight);
  return g;
}

Rows evaluate(const BsplineSurface& s) {
  Rows out(s.rows());
  for (int row = 0; row < s.rows(); ++row) s.evaluateRow(row, out[row]);
  return out;
}

// By the definition, independently of the implementation: all 4 x 4 control points
// (every c-th grid point, spans i-1 .. i+2 around i = col / c) inside and valid.
bool expectedValid(const Grid& g, int c, int col, int row) {
  for (int a = col / c - 1; a <= col / c + 2; ++a)
    for (int b = row / c - 1; b <= row / c + 2; ++b)
      if (a < 0 || b < 0 || a * c >= g.cols || b * c >= g.rows || !g.valid(a * c, b * c)) return false;
  return true;
}

int countValid(const Rows& rows) {
  int n = 0;
  for (const auto& r : rows)
    for (const SurfacePoint& p : r) n += !std::isnan(p.z);
  return n;
}

void expectAllNaN(const SurfacePoint& p) {
  EXPECT_TRUE(std::isnan(p.z));
  EXPECT_TRUE(std::isnan(p.zx));
  EXPECT_TRUE(std::isnan(p.zy));
  EXPECT_TRUE(std::isnan(p.zxx));
  EXPECT_TRUE(std::isnan(p.zxy));
  EXPECT_TRUE(std::isnan(p.zyy));
}

struct Expected {
  double z, zx, zy, zxx, zxy, zyy;
};
using ExpectedAt = std::function<Expected(double x, double y)>;

// Checks every valid point against exact values; returns how many were checked.
int expectExact(const Grid& g, int c, const std::vector<double>& w, double h, const ExpectedAt& e, double tol) {
  const Rows out = evaluate(BsplineSurface(g, c, w, h));
  int checked = 0;
  for (int row = 0; row < g.rows; ++row)
    for (int col = 0; col < g.cols; ++col) {
      const SurfacePoint& p = out[row][col];
      EXPECT_EQ(!std::isnan(p.z), expectedValid(g, c, col, row)) << col << "," << row;
      if (std::isnan(p.z)) continue;
      const Expected x = e(col * w[row], -row * h);
      EXPECT_NEAR(p.z, x.z, tol) << "c=" << c << " at " << col << "," << row;
      EXPECT_NEAR(p.zx, x.zx, tol) << "c=" << c << " at " << col << "," << row;
      EXPECT_NEAR(p.zy, x.zy, tol) << "c=" << c << " at " << col << "," << row;
      EXPECT_NEAR(p.zxx, x.zxx, tol) << "c=" << c << " at " << col << "," << row;
      EXPECT_NEAR(p.zxy, x.zxy, tol) << "c=" << c << " at " << col << "," << row;
      EXPECT_NEAR(p.zyy, x.zyy, tol) << "c=" << c << " at " << col << "," << row;
      ++checked;
    }
  return checked;
}

TEST(BsplineSurface, ReproducesAPlaneExactly) {
  const std::vector<double> w(17, 2.5);
  const Grid g = sampled(20, 17, w, 4, [](double x, double y) { return 3 + 0.7 * x - 1.3 * y; });
  for (int c : {1, 2, 3}) {
    const auto exact = [](double x, double y) { return Expected{3 + 0.7 * x - 1.3 * y, 0.7, -1.3, 0, 0, 0}; };
    const int n = expectExact(g, c, w, 4, exact, 1e-9);
    EXPECT_GT(n, 0) << "c=" << c;
  }
}

// Geographic DEMs: the metres per column change from row to row; zx uses the row's own.
TEST(BsplineSurface, UsesEachRowsCellWidth) {
  std::vector<double> w(15);
  for (int row = 0; row < 15; ++row) w[row] = 10 + 0.5 * row;
  const Grid g = sampled(16, 15, w, 7, [](double x, double) { return 0.4 * x; });
  const Rows out = evaluate(BsplineSurface(g, 2, w, 7));
  int checked = 0;
  for (int row = 0; row < 15; ++row)
    for (int col = 0; col < 16; ++col)
      if (!std::isnan(out[row][col].z)) {
        EXPECT_NEAR(out[row][col].z, 0.4 * col * w[row], 1e-9);
        EXPECT_NEAR(out[row][col].zx, 0.4, 1e-12) << col << "," << row;
        ++checked;
      }
  EXPECT_EQ(checked, 10 * 10);  // 8 x 8 control points: spans 1..5 of 2 test points
}

// A uniform cubic B-spline through samples of x^2 at spacing h is x^2 + h^2/3 (the
// variance of the cubic B-spline kernel, 4 * h^2 / 12): at a knot, (1/6)(x-h)^2 +
// (4/6)x^2 + (1/6)(x+h)^2 = x^2 + h^2/3. Its derivatives are exact.
TEST(BsplineSurface, QuadraticsHaveKnownOffsetAndExactDerivatives) {
  const double cw = 1.5, ch = 2;
  const std::vector<double> w(23, cw);
  for (int c : {1, 2, 3}) {
    const double hx = c * cw, hy = c * ch;
    const Grid gx = sampled(25, 23, w, ch, [](double x, double) { return x * x; });
    const auto xx = [&](double x, double) { return Expected{x * x + hx * hx / 3, 2 * x, 0, 2, 0, 0}; };
    EXPECT_GT(expectExact(gx, c, w, ch, xx, 1e-9), 0);
    const Grid gy = sampled(25, 23, w, ch, [](double, double y) { return y * y; });
    const auto yy = [&](double, double y) { return Expected{y * y + hy * hy / 3, 0, 2 * y, 0, 0, 2}; };
    EXPECT_GT(expectExact(gy, c, w, ch, yy, 1e-9), 0);
    const Grid gxy = sampled(25, 23, w, ch, [](double x, double y) { return x * y; });
    EXPECT_GT(expectExact(gxy, c, w, ch, [](double x, double y) { return Expected{x * y, y, x, 0, 1, 0}; }, 1e-9), 0);
  }
}

// A flat area gives exactly zero derivatives, not rounding noise: aspect and profile
// and plan curvature rely on it to recognise flat ground.
TEST(BsplineSurface, FlatGroundHasExactlyZeroDerivatives) {
  const std::vector<double> w(14, 0.37);
  const Grid g = sampled(17, 14, w, 0.29, [](double, double) { return 1234.567; });
  const Rows out = evaluate(BsplineSurface(g, 3, w, 0.29));
  EXPECT_EQ(countValid(out), 9 * 6);  // 6 x 5 control points: 3 x 2 spans of 3 x 3
  for (const auto& r : out)
    for (const SurfacePoint& p : r) {
      if (std::isnan(p.z)) continue;
      EXPECT_NEAR(p.z, 1234.567, 1e-9);
      EXPECT_EQ(p.zx, 0);
      EXPECT_EQ(p.zy, 0);
      EXPECT_EQ(p.zxx, 0);
      EXPECT_EQ(p.zxy, 0);
      EXPECT_EQ(p.zyy, 0);
    }
}

// The derivatives are those of the evaluated surface itself: central differences of
// z (and of zx across rows) between neighbouring test points agree with them. The
// spline is C2 and piecewise cubic, so the differences are accurate to O(h^2 z''').
TEST(BsplineSurface, DerivativesMatchFiniteDifferencesOfTheSurface) {
  const double cw = 0.5, ch = 0.4;
  const int cols = 130, rows = 160, c = 8;
  const std::vector<double> w(rows, cw);
  const auto wavy = [](double x, double y) { return 40 * std::sin(x / 15) * std::cos(y / 12) + 0.2 * x; };
  const Grid g = sampled(cols, rows, w, ch, wavy);
  const Rows s = evaluate(BsplineSurface(g, c, w, ch));
  const double kTol = 1e-3;  // first derivatives ~3, second ~0.2
  int checked = 0;
  for (int row = 1; row + 1 < rows; ++row)
    for (int col = 1; col + 1 < cols; ++col) {
      const SurfacePoint& p = s[row][col];
      const SurfacePoint &e = s[row][col + 1], &west = s[row][col - 1];
      const SurfacePoint &n = s[row - 1][col], &south = s[row + 1][col];
      if (std::isnan(p.z) || std::isnan(e.z) || std::isnan(west.z) || std::isnan(n.z) || std::isnan(south.z)) continue;
      EXPECT_NEAR(p.zx, (e.z - west.z) / (2 * cw), kTol) << col << "," << row;
      EXPECT_NEAR(p.zy, (n.z - south.z) / (2 * ch), kTol) << col << "," << row;
      EXPECT_NEAR(p.zxx, (e.z - 2 * p.z + west.z) / (cw * cw), kTol) << col << "," << row;
      EXPECT_NEAR(p.zyy, (n.z - 2 * p.z + south.z) / (ch * ch), kTol) << col << "," << row;
      EXPECT_NEAR(p.zxy, (n.zx - south.zx) / (2 * ch), kTol) << col << "," << row;
      ++checked;
    }
  EXPECT_GT(checked, 5000);
}

TEST(BsplineSurface, ValidPointsNeedTheWholeControlNeighbourhoodInside) {
  const auto count = [](int cols, int rows, int c) {
    const Grid g(cols, rows, 1.0);
    return countValid(evaluate(BsplineSurface(g, c, std::vector<double>(rows, 1.0), 1)));
  };
  EXPECT_EQ(count(7, 6, 1), 4 * 3);   // columns 1..4, rows 1..3
  EXPECT_EQ(count(9, 10, 2), 4 * 4);  // control columns/rows 0,2,..,8: test columns/rows 2..5
  EXPECT_EQ(count(10, 9, 2), 4 * 4);  // the last column is no control column
  EXPECT_EQ(count(11, 11, 2), 6 * 6); // control 0..10: test columns/rows 2..7
  EXPECT_EQ(count(6, 6, 2), 0);       // 3 x 3 control points: no complete span
  EXPECT_EQ(count(3, 3, 1), 0);
}

TEST(BsplineSurface, NoValueWhereAControlPointIsMissing) {
  for (int c : {1, 2}) {
    Grid g(23, 21, 5.0);
    g.at(5 * c, 4 * c) = NAN;  // a control point
    g.at(3, 9) = NAN;          // a control point for c = 1 only
    const Rows out = evaluate(BsplineSurface(g, c, std::vector<double>(21, 1.0), 1));
    int valid = 0;
    for (int row = 0; row < g.rows; ++row)
      for (int col = 0; col < g.cols; ++col) {
        const bool expected = expectedValid(g, c, col, row);
        EXPECT_EQ(!std::isnan(out[row][col].z), expected) << "c=" << c << " at " << col << "," << row;
        if (!expected) expectAllNaN(out[row][col]);
        valid += expected;
      }
    // c = 1: 20 x 18 points have all control points inside; each hole removes 4 x 4,
    // overlapping in none. c = 2: 12 control columns and 11 rows give 9 x 8 spans of 2 x 2
    // points, minus the 4 x 4 spans that use control point (5, 4).
    EXPECT_EQ(valid, c == 1 ? 20 * 18 - 2 * 16 : (9 * 8 - 16) * 4) << "c=" << c;
  }
}

TEST(BsplineSurface, YGrowsNorthAgainstTheRowIndex) {
  const std::vector<double> w(12, 3);
  const Grid g = sampled(12, 12, w, 5, [](double, double y) { return y; });  // higher to the north
  const Rows out = evaluate(BsplineSurface(g, 2, w, 5));
  EXPECT_EQ(countValid(out), 36);
  for (const auto& r : out)
    for (const SurfacePoint& p : r)
      if (!std::isnan(p.z)) {
        EXPECT_NEAR(p.zy, 1, 1e-12);
        EXPECT_NEAR(p.zx, 0, 1e-12);
      }
}

TEST(BsplineSurface, RowsEvaluatedConcurrentlyMatchSerial) {
  const int n = 64;
  const std::vector<double> w(n, 2);
  const Grid g = sampled(n, n, w, 3, [](double x, double y) { return std::sin(x / 9) * y; });
  const BsplineSurface s(g, 3, w, 3);
  const Rows serial = evaluate(s);
  Rows parallel(n);
  const auto work = [&](int first) {
    for (int row = first; row < n; row += 4) s.evaluateRow(row, parallel[row]);
  };
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) threads.emplace_back(work, t);
  for (std::thread& t : threads) t.join();
  for (int row = 0; row < n; ++row)
    for (int col = 0; col < n; ++col) {
      const SurfacePoint &a = serial[row][col], &b = parallel[row][col];
      if (std::isnan(a.z)) {
        EXPECT_TRUE(std::isnan(b.z));
        continue;
      }
      EXPECT_EQ(a.z, b.z);
      EXPECT_EQ(a.zxy, b.zxy);
    }
}

TEST(BsplineSurface, RejectsBadArguments) {
  const Grid g(8, 6, 1.0);
  EXPECT_THROW(BsplineSurface(g, 0, std::vector<double>(6, 1.0), 1), Error);
  EXPECT_THROW(BsplineSurface(g, 2, std::vector<double>(5, 1.0), 1), Error);
  EXPECT_THROW(BsplineSurface(g, 2, std::vector<double>(6, 1.0), 0), Error);
  EXPECT_THROW(BsplineSurface(g, 2, std::vector<double>(6, -1.0), 1), Error);
  const BsplineSurface s(g, 1, std::vector<double>(6, 1.0), 1);
  std::vector<SurfacePoint> out;
  EXPECT_THROW(s.evaluateRow(6, out), Error);
  EXPECT_THROW(s.evaluateRow(-1, out), Error);
}

}  // namespace
}  // namespace tinlod
