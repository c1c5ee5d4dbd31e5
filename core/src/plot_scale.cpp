// SPDX-License-Identifier: GPL-3.0-or-later
#include "plot_scale.h"

#include <algorithm>
#include <cmath>

namespace tinlod {
namespace {

// Tolerance for values that land on a tick up to rounding (3 * 0.1 is not 0.3).
constexpr double kSlack = 1e-9;

double niceStep(double rough) {
  const double decade = std::pow(10.0, std::floor(std::log10(rough)));
  const double mantissa = rough / decade;
  return (mantissa <= 1 ? 1 : mantissa <= 2 ? 2 : mantissa <= 5 ? 5 : 10) * decade;
}

AxisScale linearScale(AxisScale s, double min, double max) {
  if (!(max - min > kSlack * std::max(std::fabs(min), std::fabs(max)))) {
    const double pad = max != 0 ? std::fabs(max) * 0.1 : 1;  // a single value sits mid-axis
    min -= pad;
    max += pad;
  }
  const double step = niceStep((max - min) / 5);
  s.lo = std::floor(min / step + kSlack) * step;
  s.hi = std::ceil(max / step - kSlack) * step;
  const long count = std::lround((s.hi - s.lo) / step);
  for (long i = 0; i <= count; ++i) {
    const double tick = s.lo + static_cast<double>(i) * step;
    s.ticks.push_back(std::fabs(tick) < step * kSlack ? 0.0 : tick);  // no "-0"
  }
  return s;
}

// 1, 2 and 5 times each power of ten around [min, max] (only 1 when `decadesOnly`).
std::vector<double> logCandidates(double min, double max, bool decadesOnly) {
  std::vector<double> out;
  const int first = static_cast<int>(std::floor(std::log10(min))) - 1;
  const int last = static_cast<int>(std::ceil(std::log10(max))) + 1;
  for (int d = first; d <= last; ++d)
    for (double m : {1.0, 2.0, 5.0})
      if (m == 1 || !decadesOnly) out.push_back(m * std::pow(10.0, d));
  return out;
}

AxisScale logScale(AxisScale s, double min, double max) {
  s.log = true;
  const std::vector<double> candidates = logCandidates(min, max, std::log10(max / min) > 3);
  double lo = candidates.front(), hi = candidates.back();
  for (double c : candidates)
    if (c <= min * (1 + kSlack)) lo = c;
  for (auto c = candidates.rbegin(); c != candidates.rend(); ++c)
    if (*c >= max * (1 - kSlack)) hi = *c;
  for (double c : candidates)
    if (c >= lo && c <= hi) s.ticks.push_back(c);
  s.lo = std::log10(lo);
  s.hi = std::log10(hi);
  return s;
}

}  // namespace

bool AxisScale::plottable(double value) const { return std::isfinite(value) && (!log || value > 0); }

double AxisScale::pixel(double value) const {
  const double t = ((log ? std::log10(value) : value) - lo) / (hi - lo);
  return from + t * (to - from);
}

bool spansWideRange(const std::vector<double>& values) {
  double min = INFINITY, max = -INFINITY;
  for (double v : values)
    if (std::isfinite(v)) {
      min = std::min(min, v);
      max = std::max(max, v);
    }
  return min > 0 && std::isfinite(max) && max > 20 * min;
}

AxisScale makeScale(const std::vector<double>& values, AxisKind kind, bool fromZero, double from, double to) {
  AxisScale s;
  s.from = from;
  s.to = to;
  const bool log = kind == AxisKind::Log || (kind == AxisKind::Auto && spansWideRange(values));
  std::vector<double> usable;
  std::copy_if(values.begin(), values.end(), std::back_inserter(usable),
               [&](double v) { return std::isfinite(v) && (!log || v > 0); });
  if (usable.empty()) return linearScale(s, 0, 1);
  double min = *std::min_element(usable.begin(), usable.end());
  double max = *std::max_element(usable.begin(), usable.end());
  if (log) return logScale(s, min == max ? min / 2 : min, min == max ? max * 2 : max);
  if (fromZero) {
    min = std::min(min, 0.0);
    max = std::max(max, min == 0 && max == 0 ? 1.0 : 0.0);  // all zero: 0 at the bottom, not mid-axis
  }
  return linearScale(s, min, max);
}

}  // namespace tinlod
