// SPDX-License-Identifier: GPL-3.0-or-later
// Private: where values go along a plot axis, and the round numbers that label it.
#pragma once

#include <vector>

namespace tinlod {

enum class AxisKind {
  Auto,  // logarithmic when the values are wide (below), else linear
  Linear,
  Log,  // values <= 0 are left out
};

struct AxisScale {
  bool log = false;
  double lo = 0, hi = 1;      // the domain; its log10 on a logarithmic axis
  double from = 0, to = 1;    // the pixels lo and hi map to
  std::vector<double> ticks;  // values (not their log10), lo and hi among them

  // Finite, and positive on a logarithmic axis.
  bool plottable(double value) const;
  double pixel(double value) const;
};

// True when every finite value is positive and the largest is more than 20 times the
// smallest: then a linear axis would crowd the small ones into a corner.
bool spansWideRange(const std::vector<double>& values);

// An axis over `values` (NaN and infinities ignored) from pixel `from` to `to`, ending on
// ticks: 1-2-5 steps (from 0 when `fromZero`), or on a logarithmic axis 1-2-5 within each
// decade (decades only when they are more than three). No values, or all equal, still
// give a usable range.
AxisScale makeScale(const std::vector<double>& values, AxisKind kind, bool fromZero, double from, double to);

}  // namespace tinlod
