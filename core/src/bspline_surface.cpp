// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/bspline_surface.h"

#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "tinlod/error.h"

namespace tinlod {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The uniform cubic B-spline basis matrix (times 6).
constexpr double kBasis[4][4] = {{-1, 3, -3, 1}, {3, -6, 3, 0}, {-3, 0, 3, 0}, {1, 4, 1, 0}};

// Weights of the 4 control points for the powers `powers` of t: powers * M.
void applyBasis(const double (&powers)[4], double (&weights)[4]) {
  for (int j = 0; j < 4; ++j) {
    weights[j] = 0;
    for (int m = 0; m < 4; ++m) weights[j] += powers[m] * kBasis[m][j] / 6;
  }
}

// Rewrites weights that sum to zero as weights of the forward differences
// (w . P = b . dP with b_k = -(w_0 + ... + w_k)). Derivatives taken from
// differences are exactly 0 on constant data, so a flat area stays exactly flat.
template <int N>
void toDifferences(const double (&weights)[N], double (&out)[N - 1]) {
  double sum = 0;
  for (int k = 0; k < N - 1; ++k) out[k] = -(sum += weights[k]);
}

double dot4(const double (&w)[4], const double* c) { return w[0] * c[0] + w[1] * c[1] + w[2] * c[2] + w[3] * c[3]; }
double dot3(const double (&w)[3], const double* c) { return w[0] * c[0] + w[1] * c[1] + w[2] * c[2]; }
double dot2(const double (&w)[2], const double* c) { return w[0] * c[0] + w[1] * c[1]; }

void checkArguments(const Grid& values, int spacing, const std::vector<double>& cellWidth, double cellHeight) {
  if (values.cols < 0 || values.rows < 0 ||
      values.values.size() != static_cast<std::size_t>(values.cols) * static_cast<std::size_t>(values.rows))
    throw Error("B-spline grid: the values do not match its " + std::to_string(values.cols) + " x " +
                std::to_string(values.rows) + " size");
  if (spacing < 1) throw Error("B-spline control spacing must be at least 1, got " + std::to_string(spacing));
  if (cellWidth.size() != static_cast<std::size_t>(values.rows))
    throw Error("B-spline cell widths: expected one per row (" + std::to_string(values.rows) + "), got " +
                std::to_string(cellWidth.size()));
  for (double w : cellWidth)
    if (!(w > 0) || !std::isfinite(w)) throw Error("B-spline cell widths must be positive and finite");
  if (!(cellHeight > 0) || !std::isfinite(cellHeight)) throw Error("B-spline cell height must be positive and finite");
}

}  // namespace

// The only c values of t that occur (t = k / c), so the weights are computed once.
BsplineSurface::Weights BsplineSurface::basisWeights(double t) {
  Weights w;
  double first[4], second[4], secondDiff[3];
  applyBasis({t * t * t, t * t, t, 1}, w.value);
  applyBasis({3 * t * t, 2 * t, 1, 0}, first);
  applyBasis({6 * t, 2, 0, 0}, second);
  toDifferences(first, w.slope);
  toDifferences(second, secondDiff);
  toDifferences(secondDiff, w.bend);
  return w;
}

// The 4 control rows around one test row blended into one curve per control column:
// value (c0), v-derivative (c1), second v-derivative (c2), and the forward differences
// along u that the u-derivatives need (d0, dd0 of c0; d1 of c1). Blending the rows once
// per row makes each point cost 4-term sums instead of 16-term ones.
struct BsplineSurface::RowBlend {
  std::vector<double> buffer;
  double *c0, *c1, *c2, *d0, *dd0, *d1;
};

BsplineSurface::BsplineSurface(const Grid& values, int controlSpacing, std::vector<double> cellWidth, double cellHeight)
    : values_(values), spacing_(controlSpacing), cellWidth_(std::move(cellWidth)), cellHeight_(cellHeight) {
  checkArguments(values, controlSpacing, cellWidth_, cellHeight);
  controlCols_ = values.cols > 0 ? (values.cols - 1) / spacing_ + 1 : 0;
  controlRows_ = values.rows > 0 ? (values.rows - 1) / spacing_ + 1 : 0;
  for (int k = 0; k < spacing_; ++k) weights_.push_back(basisWeights(double(k) / spacing_));
}

int BsplineSurface::cols() const { return values_.cols; }
int BsplineSurface::rows() const { return values_.rows; }

void BsplineSurface::blendControlRows(int row, RowBlend& b) const {
  const int n = controlCols_;
  b.buffer.resize(6 * static_cast<std::size_t>(n));
  b.c0 = b.buffer.data();
  b.c1 = b.c0 + n;
  b.c2 = b.c1 + n;
  b.d0 = b.c2 + n;
  b.dd0 = b.d0 + n;
  b.d1 = b.dd0 + n;
  const Weights& w = weights_[row % spacing_];
  const double* p[4];
  for (int k = 0; k < 4; ++k)
    p[k] = &values_.values[static_cast<std::size_t>(row / spacing_ - 1 + k) * spacing_ * values_.cols];
  for (int a = 0; a < n; ++a) {
    const std::size_t x = static_cast<std::size_t>(a) * spacing_;
    const double v[4] = {p[0][x], p[1][x], p[2][x], p[3][x]};
    const double dv[3] = {v[1] - v[0], v[2] - v[1], v[3] - v[2]};
    const double ddv[2] = {dv[1] - dv[0], dv[2] - dv[1]};
    b.c0[a] = dot4(w.value, v);
    b.c1[a] = dot3(w.slope, dv);
    b.c2[a] = dot2(w.bend, ddv);
  }
  for (int a = 0; a + 1 < n; ++a) {
    b.d0[a] = b.c0[a + 1] - b.c0[a];
    b.d1[a] = b.c1[a + 1] - b.c1[a];
  }
  for (int a = 0; a + 2 < n; ++a) b.dd0[a] = b.d0[a + 1] - b.d0[a];
}

void BsplineSurface::evaluateRow(int row, std::vector<SurfacePoint>& out) const {
  if (row < 0 || row >= values_.rows) throw Error("B-spline row " + std::to_string(row) + " is outside the grid");
  const SurfacePoint none{kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};
  out.assign(static_cast<std::size_t>(values_.cols), none);
  const int span = row / spacing_;
  if (span < 1 || span + 2 >= controlRows_ || controlCols_ < 4) return;
  // A buffer per call, not a member: rows are evaluated concurrently on one surface,
  // and one allocation per row is negligible against the row's points.
  RowBlend b;
  blendControlRows(row, b);
  const double sx = 1 / (spacing_ * cellWidth_[row]);
  const double sy = 1 / (spacing_ * cellHeight_);  // y grows north, the row index south
  for (int i = 1; i + 2 < controlCols_; ++i) {
    for (int k = 0; k < spacing_; ++k) {
      const int col = i * spacing_ + k;
      if (col >= values_.cols) return;
      const Weights& w = weights_[k];
      const double z = dot4(w.value, b.c0 + i - 1);
      if (std::isnan(z)) continue;
      SurfacePoint& s = out[col];
      s.z = z;
      s.zx = dot3(w.slope, b.d0 + i - 1) * sx;
      s.zy = -dot4(w.value, b.c1 + i - 1) * sy;
      s.zxx = dot2(w.bend, b.dd0 + i - 1) * sx * sx;
      s.zxy = -dot3(w.slope, b.d1 + i - 1) * sx * sy;
      s.zyy = dot4(w.value, b.c2 + i - 1) * sy * sy;
    }
  }
}

}  // namespace tinlod
