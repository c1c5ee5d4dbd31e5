// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/terrain_measures.h"

#include <cmath>
#include <limits>

namespace tinlod {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDegrees = 57.29577951308232;  // 180 / pi

// Squared gradient at or below which a point counts as flat (gradient <= 1e-12, far
// below any terrain slope): its downslope direction, and with it aspect, profile and
// plan curvature, is undefined rather than numerical noise amplified to any size.
constexpr double kFlatGradient2 = 1e-24;

// atan2(-p, -q) as a compass bearing in [0, 360).
double downslopeAzimuth(double p, double q) {
  double a = std::atan2(-p, -q) * kDegrees;
  if (a < 0) a += 360;
  return a >= 360 ? 0 : a;
}

}  // namespace

TerrainMeasures terrainMeasures(const SurfacePoint& pt) {
  if (std::isnan(pt.z)) return {kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};
  TerrainMeasures m;
  m.z = pt.z;
  const double p = pt.zx, q = pt.zy, r = pt.zxx, s = pt.zxy, t = pt.zyy;
  const double p2 = p * p, q2 = q * q, g2 = p2 + q2;
  const double w2 = 1 + g2;
  const double w3 = w2 * std::sqrt(w2);
  m.meanCurvature = ((1 + q2) * r - 2 * p * q * s + (1 + p2) * t) / (2 * w3);
  m.gaussianCurvature = (r * t - s * s) / (w2 * w2);
  m.slope = std::atan(std::sqrt(g2)) * kDegrees;
  if (!(g2 > kFlatGradient2)) {
    m.aspect = m.profileCurvature = m.planCurvature = kNaN;
    return m;
  }
  m.aspect = downslopeAzimuth(p, q);
  m.profileCurvature = -(p2 * r + 2 * p * q * s + q2 * t) / (g2 * w3);
  m.planCurvature = -(q2 * r - 2 * p * q * s + p2 * t) / (g2 * std::sqrt(g2));
  return m;
}

}  // namespace tinlod
