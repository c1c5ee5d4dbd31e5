// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tinlod/concavity.h"

namespace tinlod {
namespace {

const double kPi = std::acos(-1.0);

// A circle of radius r counter-clockwise from angle a0 to a1 (its centre on the left).
Polyline arc(double r, double a0, double a1, int points) {
  Polyline line;
  for (int i = 0; i < points; ++i) {
    const double a = a0 + (a1 - a0) * i / (points - 1);
    line.push_back({5000 + r * std::cos(a), 7000 + r * std::sin(a)});
  }
  return line;
}

Polyline reversed(Polyline line) {
  std::reverse(line.begin(), line.end());
  return line;
}

// The secant measure straight from its definition: walk to the window's ends, close the
// section with the secant and take its area.
double secantByDefinition(const Polyline& line, std::size_t i, double d) {
  std::vector<double> s(line.size(), 0);
  for (std::size_t k = 1; k < line.size(); ++k) s[k] = s[k - 1] + std::hypot(line[k][0] - line[k - 1][0], line[k][1] - line[k - 1][1]);
  if (s[i] < d || s[i] + d > s.back()) return NAN;
  auto pointAt = [&](double at) {
    std::size_t k = 0;
    while (k + 2 < line.size() && s[k + 1] < at) ++k;
    const double t = (at - s[k]) / (s[k + 1] - s[k]);
    return LinePoint{line[k][0] + t * (line[k + 1][0] - line[k][0]), line[k][1] + t * (line[k + 1][1] - line[k][1])};
  };
  Polyline polygon{pointAt(s[i] - d)};
  for (std::size_t k = 0; k < line.size(); ++k)
    if (s[k] > s[i] - d && s[k] < s[i] + d) polygon.push_back(line[k]);
  polygon.push_back(pointAt(s[i] + d));
  double area = 0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const LinePoint &a = polygon[k], &b = polygon[(k + 1) % polygon.size()];
    area += (a[0] - polygon[0][0]) * (b[1] - polygon[0][1]) - (a[1] - polygon[0][1]) * (b[0] - polygon[0][0]);
  }
  const LinePoint &t = polygon.front(), &h = polygon.back();
  const double secant2 = (h[0] - t[0]) * (h[0] - t[0]) + (h[1] - t[1]) * (h[1] - t[1]);
  return secant2 < 0.01 * d * d ? NAN : -0.5 * area / secant2;  // a secant under d / 10: undefined
}

TEST(Concavity, StraightLineIsZeroAndEndsHaveNoValue) {
  Polyline line;
  for (int i = 0; i <= 100; ++i) line.push_back({1000.0 + 3 * i, 2000.0 + 4 * i});  // 5 m steps
  const std::vector<double> secant = secantConcavity(line, 50), disk = diskConcavity(line, 40);
  for (int i = 0; i <= 100; ++i) {
    if (i < 10 || i > 90) {
      EXPECT_TRUE(std::isnan(secant[i])) << i;
    } else {
      EXPECT_NEAR(secant[i], 0, 1e-12) << i;
    }
    if (i >= 9 && i <= 91) EXPECT_NEAR(disk[i], 0, 1e-9) << i;
  }
  EXPECT_TRUE(std::isnan(disk[3]));  // the line ends inside the disk
}

TEST(Concavity, CircleArcMatchesTheClosedFormsAndFlipsWhenReversed) {
  const double R = 300, d = 120, r = 150;
  const Polyline line = arc(R, 0, 2 * kPi * 0.9, 20000);
  const std::size_t mid = 10000;
  // Secant: the circular segment over the chord squared, theta = d / R.
  const double theta = d / R;
  const double secantExact = -(2 * theta - std::sin(2 * theta)) / (8 * std::sin(theta) * std::sin(theta));
  EXPECT_NEAR(secantConcavity(line, d)[mid], secantExact, 1e-6);
  EXPECT_NEAR(secantConcavity(reversed(line), d)[mid], -secantExact, 1e-6);
  // Disk: the lens of the disk and the circle (centres R apart) over the disk.
  const double lens = r * r * std::acos(r / (2 * R)) + R * R * std::acos(1 - r * r / (2 * R * R)) -
                      0.5 * r * std::sqrt(4 * R * R - r * r);
  const double diskExact = 2 * lens / (kPi * r * r) - 1;
  EXPECT_NEAR(diskConcavity(line, r)[mid], diskExact, 1e-5);
  EXPECT_NEAR(diskConcavity(reversed(line), r)[mid], -diskExact, 1e-5);
  EXPECT_LT(diskExact, 0);  // the circle's inside, on the left, is convex: less than half the disk
}

TEST(Concavity, AClosedContourHasNoEnds) {
  const double R = 200, d = 50, r = 80;
  Polyline ring = arc(R, 0, 2 * kPi, 2001);
  ring.back() = ring.front();  // closed exactly
  const std::vector<double> secant = secantConcavity(ring, d), disk = diskConcavity(ring, r);
  const double theta = d / R;
  const double secantExact = -(2 * theta - std::sin(2 * theta)) / (8 * std::sin(theta) * std::sin(theta));
  for (std::size_t i : {std::size_t(0), std::size_t(1), std::size_t(1000), ring.size() - 1}) {
    EXPECT_NEAR(secant[i], secantExact, 1e-4) << i;
    EXPECT_FALSE(std::isnan(disk[i])) << i;
    EXPECT_NEAR(disk[i], disk[1000], 1e-6) << i;
  }
  // A window reaching round the ring to itself measures nothing.
  const std::vector<double> tooWide = secantConcavity(ring, 0.51 * 2 * kPi * R);
  for (double v : tooWide) EXPECT_TRUE(std::isnan(v));
}

// A line that turns back on itself within the window has a secant far shorter than the
// window: its ratio would be huge (2.9e10 on a real contour), so it is undefined there.
TEST(Concavity, ASecantShorterThanATenthOfTheWindowMeasuresNothing) {
  const double R = 100, perimeter = 2 * kPi * R;
  Polyline ring = arc(R, 0, 2 * kPi, 4001);
  ring.back() = ring.front();
  // Half the perimeter and a little: the window's ends come 3 cm apart.
  for (double v : secantConcavity(ring, 0.49995 * perimeter)) EXPECT_TRUE(std::isnan(v));
  // A hairpin: out 500 m east, a half circle of radius 4 m, back west.
  Polyline hairpin;
  for (int i = 0; i <= 100; ++i) hairpin.push_back({5.0 * i, 0});
  for (int i = 1; i < 20; ++i) hairpin.push_back({500 + 4 * std::sin(kPi * i / 20), 4 - 4 * std::cos(kPi * i / 20)});
  for (int i = 100; i >= 0; --i) hairpin.push_back({5.0 * i, 8});
  const std::vector<double> secant = secantConcavity(hairpin, 100);
  std::size_t measured = 0;
  for (std::size_t i = 0; i < hairpin.size(); ++i) {
    if (std::isnan(secant[i])) continue;
    ++measured;
    EXPECT_LT(std::fabs(secant[i]), 32) << "vertex " << i;
  }
  EXPECT_TRUE(std::isnan(secant[110]));  // the bend: its ends 8 m apart, 100 m along each arm
  EXPECT_GT(measured, 100u);             // the arms, away from the bend, are measured
}

TEST(Concavity, TheSweepMatchesTheDefinitionEverywhere) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> turn(-0.6, 0.6), step(1, 20);
  Polyline line{{410000, 5200000}};
  double heading = 0;
  for (int i = 0; i < 500; ++i) {
    heading += turn(rng);
    const double len = step(rng);
    line.push_back({line.back()[0] + len * std::cos(heading), line.back()[1] + len * std::sin(heading)});
  }
  for (double d : {15.0, 60.0, 250.0}) {
    const std::vector<double> sweep = secantConcavity(line, d);
    for (std::size_t i = 0; i < line.size(); ++i) {
      const double brute = secantByDefinition(line, i, d);
      if (std::isnan(brute)) {
        EXPECT_TRUE(std::isnan(sweep[i])) << i;
      } else {
        EXPECT_NEAR(sweep[i], brute, 1e-9 * (1 + std::fabs(brute))) << "vertex " << i << ", window " << d;
      }
    }
  }
}

TEST(Concavity, PartsFollowTheBends) {
  // Straight east, a left turn (a quarter circle), straight north.
  Polyline line;
  for (int i = 0; i < 50; ++i) line.push_back({double(i) * 2, 0});
  for (const LinePoint& p : arc(60, -kPi / 2, 0, 60)) line.push_back({p[0] - 5000 + 100, p[1] - 7000 + 60});
  for (int i = 1; i < 50; ++i) line.push_back({160, 60 + 2.0 * i});
  const std::vector<LinePart> parts = curvatureParts(line, secantConcavity(line, 10), 0.02);
  ASSERT_EQ(parts.size(), 3u);
  EXPECT_EQ(parts[0].curvature, Curvature::Straight);
  EXPECT_EQ(parts[1].curvature, Curvature::Concave);  // a left turn bulges to the right: concave from the left
  EXPECT_EQ(parts[2].curvature, Curvature::Straight);
  EXPECT_EQ(parts[0].line.back(), parts[1].line.front());
  EXPECT_EQ(curvatureName(Curvature::Concave), "concave");
}

}  // namespace
}  // namespace tinlod
