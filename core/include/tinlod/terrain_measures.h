// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "tinlod/bspline_surface.h"

namespace tinlod {

// Geomorphometric variables of a surface point z(x, y), from p = zx, q = zy,
// r = zxx, s = zxy, t = zyy (x east, y north, metres) and W = sqrt(1 + p^2 + q^2).
// Curvatures are in 1/m (Gaussian 1/m^2); "flat" means p^2 + q^2 <= 1e-24.
struct TerrainMeasures {
  double z = 0;
  // H = ((1 + q^2) r - 2 p q s + (1 + p^2) t) / (2 W^3), for the upward normal:
  // > 0 in a bowl or valley, < 0 on a dome or ridge; a sphere cap of radius R gives -1/R.
  double meanCurvature = 0;
  // K = (r t - s^2) / W^4: > 0 on domes and bowls, < 0 on saddles, 0 on planes and cylinders.
  double gaussianCurvature = 0;
  // atan(sqrt(p^2 + q^2)) in degrees from horizontal.
  double slope = 0;
  // Compass bearing of the downslope direction (-p, -q), degrees clockwise from north in
  // [0, 360): a slope falling to the east has 90, to the south 180. NaN where flat.
  double aspect = 0;
  // Florinsky's vertical curvature k_v = -(p^2 r + 2 p q s + q^2 t) / ((p^2 + q^2) W^3),
  // the normal curvature along the slope line: > 0 where the slope steepens downhill
  // (convex profile, flow accelerates), < 0 where it eases (concave profile). NaN where flat.
  double profileCurvature = 0;
  // Contour (plan) curvature k_p = -(q^2 r - 2 p q s + p^2 t) / (p^2 + q^2)^(3/2): > 0 where
  // contours bend around a spur (flow diverges; 1/rho at distance rho from the top of a cone),
  // < 0 in a hollow (flow converges). NaN where flat.
  double planCurvature = 0;
};

// All NaN when p.z is NaN.
TerrainMeasures terrainMeasures(const SurfacePoint& p);

}  // namespace tinlod
