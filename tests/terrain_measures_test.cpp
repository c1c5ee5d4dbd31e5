// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>

#include "tinlod/terrain_measures.h"

namespace tinlod {
namespace {

const double kPi = std::acos(-1.0);

double degrees(double radians) { return radians * 180 / kPi; }

// z = sign * sqrt(R^2 - x^2 - y^2): a sphere cap (sign +1) or a bowl (sign -1).
SurfacePoint sphere(double R, double x, double y, double sign = 1) {
  const double w = std::sqrt(R * R - x * x - y * y), w3 = w * w * w;
  return {sign * w, -sign * x / w, -sign * y / w, -sign * (R * R - y * y) / w3, -sign * x * y / w3,
          -sign * (R * R - x * x) / w3};
}

// z = sqrt(R^2 - x^2): a cylinder with its axis along y.
SurfacePoint cylinder(double R, double x) {
  const double w = std::sqrt(R * R - x * x);
  return {w, -x / w, 0, -R * R / (w * w * w), 0, 0};
}

// z = k * rho, rho = sqrt(x^2 + y^2): a pit cone for k > 0, a peak for k < 0.
SurfacePoint cone(double k, double x, double y) {
  const double rho = std::hypot(x, y), r3 = rho * rho * rho;
  return {k * rho, k * x / rho, k * y / rho, k * y * y / r3, -k * x * y / r3, k * x * x / r3};
}

// z = a * u^2 with u = x cos(theta) + y sin(theta): parabolic cross-section, straight contours.
SurfacePoint parabolicTrough(double a, double theta, double x, double y) {
  const double c = std::cos(theta), s = std::sin(theta), u = x * c + y * s;
  return {a * u * u, 2 * a * u * c, 2 * a * u * s, 2 * a * c * c, 2 * a * c * s, 2 * a * s * s};
}

SurfacePoint plane(double p, double q) { return {10, p, q, 0, 0, 0}; }

const double kSpherePoints[][2] = {{0, 0}, {30, -20}, {-50, 40}, {60, 55}, {-5, -80}};

TEST(TerrainMeasures, SphereCapHasMeanCurvatureMinusOneOverR) {
  const double R = 100;
  for (const auto& xy : kSpherePoints) {
    const TerrainMeasures m = terrainMeasures(sphere(R, xy[0], xy[1]));
    EXPECT_NEAR(m.meanCurvature, -1 / R, 1e-12) << xy[0] << "," << xy[1];
    EXPECT_NEAR(m.gaussianCurvature, 1 / (R * R), 1e-14) << xy[0] << "," << xy[1];
  }
}

TEST(TerrainMeasures, BowlHasMeanCurvaturePlusOneOverR) {
  const double R = 250;
  for (const auto& xy : kSpherePoints) {
    const TerrainMeasures m = terrainMeasures(sphere(R, xy[0], xy[1], -1));
    EXPECT_NEAR(m.meanCurvature, 1 / R, 1e-12) << xy[0] << "," << xy[1];
    EXPECT_NEAR(m.gaussianCurvature, 1 / (R * R), 1e-14) << xy[0] << "," << xy[1];
  }
}

TEST(TerrainMeasures, CylinderHasHalfTheMeanCurvatureAndNoGaussian) {
  const double R = 40;
  for (double x : {0.0, 12.0, -25.0, 35.0}) {
    const TerrainMeasures m = terrainMeasures(cylinder(R, x));
    EXPECT_NEAR(m.meanCurvature, -1 / (2 * R), 1e-12) << x;
    EXPECT_NEAR(m.gaussianCurvature, 0, 1e-15) << x;
  }
}

TEST(TerrainMeasures, SaddleAtItsCentre) {
  const TerrainMeasures m = terrainMeasures({0, 0, 0, 1, 0, -1});  // z = (x^2 - y^2) / 2
  EXPECT_DOUBLE_EQ(m.meanCurvature, 0);
  EXPECT_DOUBLE_EQ(m.gaussianCurvature, -1);
  EXPECT_DOUBLE_EQ(m.slope, 0);
  const TerrainMeasures twisted = terrainMeasures({0, 0, 0, 0, 0.5, 0});  // z = x y / 2
  EXPECT_DOUBLE_EQ(twisted.gaussianCurvature, -0.25);
}

TEST(TerrainMeasures, PlaneSlopeAndAspect) {
  struct Case {
    double p, q, aspect;
  } cases[] = {
      {-1, 0, 90},                                 // falls to the east
      {0, 1, 180},                                 // rises to the north: falls to the south
      {0, -0.2, 0},                                // falls to the north
      {0.3, 0, 270},                               // falls to the west
      {-0.5, -0.5, 45},                            // falls to the north-east
      {0.5, 0.5, 225},                             // falls to the south-west
      {-std::sqrt(3.0), 1, 120},                   // 30 degrees south of east
      {1e-9, -1, 360 - degrees(std::atan(1e-9))},  // just west of north, not 360
  };
  for (const Case& c : cases) {
    const TerrainMeasures m = terrainMeasures(plane(c.p, c.q));
    EXPECT_NEAR(m.aspect, c.aspect, 1e-9) << c.p << "," << c.q;
    EXPECT_NEAR(m.slope, degrees(std::atan(std::hypot(c.p, c.q))), 1e-12) << c.p << "," << c.q;
    EXPECT_EQ(m.meanCurvature, 0);
    EXPECT_EQ(m.gaussianCurvature, 0);
    EXPECT_EQ(m.profileCurvature, 0);
    EXPECT_EQ(m.planCurvature, 0);
    EXPECT_DOUBLE_EQ(m.z, 10);
  }
  EXPECT_DOUBLE_EQ(terrainMeasures(plane(1, 0)).slope, 45);
  const double a = terrainMeasures(plane(0, -1e-300)).aspect;  // below the flat limit
  EXPECT_TRUE(std::isnan(a));
  EXPECT_GE(terrainMeasures(plane(-1e-30, -1)).aspect, 0);
  EXPECT_LT(terrainMeasures(plane(1e-30, -1)).aspect, 360);
}

TEST(TerrainMeasures, FlatPointHasNoDirection) {
  const TerrainMeasures m = terrainMeasures({5, 0, 0, 2, 0, 2});  // bottom of z = x^2 + y^2
  EXPECT_DOUBLE_EQ(m.slope, 0);
  EXPECT_DOUBLE_EQ(m.meanCurvature, 2);
  EXPECT_DOUBLE_EQ(m.gaussianCurvature, 4);
  EXPECT_TRUE(std::isnan(m.aspect));
  EXPECT_TRUE(std::isnan(m.profileCurvature));
  EXPECT_TRUE(std::isnan(m.planCurvature));
}

TEST(TerrainMeasures, MissingHeightGivesNothing) {
  const TerrainMeasures m = terrainMeasures({NAN, 1, 1, 1, 1, 1});
  for (double v : {m.z, m.meanCurvature, m.gaussianCurvature, m.slope, m.aspect, m.profileCurvature, m.planCurvature})
    EXPECT_TRUE(std::isnan(v));
}

// Contours of a cone are circles around its axis: plan curvature 1/rho around a peak
// (flow diverges), -1/rho around a pit; slope lines are straight: no profile curvature.
TEST(TerrainMeasures, ConePlanCurvatureIsOneOverDistance) {
  const double points[][2] = {{10, 0}, {0, -7}, {3, 4}, {-6, 8}, {-20, -21}};
  for (const auto& xy : points) {
    const double rho = std::hypot(xy[0], xy[1]);
    const TerrainMeasures peak = terrainMeasures(cone(-0.6, xy[0], xy[1]));
    EXPECT_NEAR(peak.planCurvature, 1 / rho, 1e-12) << xy[0] << "," << xy[1];
    EXPECT_NEAR(peak.profileCurvature, 0, 1e-14) << xy[0] << "," << xy[1];
    EXPECT_NEAR(peak.aspect, std::fmod(degrees(std::atan2(xy[0], xy[1])) + 360, 360), 1e-9);  // away from the top
    const TerrainMeasures pit = terrainMeasures(cone(2.5, xy[0], xy[1]));
    EXPECT_NEAR(pit.planCurvature, -1 / rho, 1e-12) << xy[0] << "," << xy[1];
    EXPECT_NEAR(pit.profileCurvature, 0, 1e-14) << xy[0] << "," << xy[1];
  }
}

// A parabolic cross-section in any direction: the slope line is the parabola z = a u^2,
// whose curvature is 2a / (1 + (2au)^2)^(3/2); profile curvature is its negative
// (concave, easing downhill: < 0; convex brow: > 0). Contours are straight: no plan curvature.
TEST(TerrainMeasures, ProfileCurvatureOfAParabolicSlope) {
  for (double theta : {0.0, 0.5, kPi / 2, 2.0, 4.0}) {
    for (double a : {1.0, -0.25}) {
      const double x = 1.5, y = -0.7, u = x * std::cos(theta) + y * std::sin(theta);
      const double expected = -2 * a / std::pow(1 + 4 * a * a * u * u, 1.5);
      const TerrainMeasures m = terrainMeasures(parabolicTrough(a, theta, x, y));
      EXPECT_NEAR(m.profileCurvature, expected, 1e-12) << theta << " " << a;
      EXPECT_NEAR(m.planCurvature, 0, 1e-12) << theta << " " << a;
    }
  }
  // z = x^2 at x = 1: p = 2, r = 2.
  EXPECT_NEAR(terrainMeasures({1, 2, 0, 2, 0, 0}).profileCurvature, -2 / std::pow(5.0, 1.5), 1e-15);
}

// On a sphere every normal section has curvature 1/R: a cap is convex along its slope
// lines (profile +1/R) and its contours are circles of radius rho (plan +1/rho).
TEST(TerrainMeasures, SphereProfileAndPlanCurvature) {
  const double R = 100;
  for (const auto& xy : kSpherePoints) {
    const double rho = std::hypot(xy[0], xy[1]);
    if (rho == 0) continue;
    const TerrainMeasures cap = terrainMeasures(sphere(R, xy[0], xy[1]));
    EXPECT_NEAR(cap.profileCurvature, 1 / R, 1e-12) << xy[0] << "," << xy[1];
    EXPECT_NEAR(cap.planCurvature, 1 / rho, 1e-12) << xy[0] << "," << xy[1];
    const TerrainMeasures bowl = terrainMeasures(sphere(R, xy[0], xy[1], -1));
    EXPECT_NEAR(bowl.profileCurvature, -1 / R, 1e-12) << xy[0] << "," << xy[1];
    EXPECT_NEAR(bowl.planCurvature, -1 / rho, 1e-12) << xy[0] << "," << xy[1];
  }
}

}  // namespace
}  // namespace tinlod
