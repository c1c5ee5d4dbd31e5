// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

namespace tinlod {

// A triangle's plane as slopes from one corner: z = z + dzdx (px - x) + dzdy (py - y).
// Measuring many points (samples, DEM cells) against a few triangles, each plane is
// worked out once.
struct TrianglePlane {
  double x, y, z, dzdx, dzdy;

  // Through the corners a, b and c, which must not be collinear in x/y.
  static TrianglePlane through(double ax, double ay, double az, double bx, double by, double bz, double cx, double cy,
                               double cz) {
    const double d = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay);
    return {ax, ay, az, ((bz - az) * (cy - ay) - (cz - az) * (by - ay)) / d,
            ((cz - az) * (bx - ax) - (bz - az) * (cx - ax)) / d};
  }
  double height(double px, double py) const { return z + dzdx * (px - x) + dzdy * (py - y); }
};

}  // namespace tinlod
