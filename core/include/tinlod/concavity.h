// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>
#include <vector>

#include "tinlod/douglas_peucker.h"

namespace tinlod {

// The secant concavity of every vertex: with the points a distance `window` along the
// line before and after it, the signed area between the line and the secant joining them
// over the secant's length squared. Positive where the line bulges to its left (convex
// seen from the left side), 0 on a straight line; NaN within `window` of an endpoint, and
// where the secant is shorter than a tenth of `window` (the line turned back on itself:
// the ratio would grow without bound; at a tenth it is at most about 35, a near-full circle).
// One sweep: the window's ends move along with the vertex and the area comes from
// prefix sums, O(n) for the whole line. A closed line (first vertex = last) has no ends:
// it is measured around (both measures), where twice the window (radius) is shorter
// than its perimeter; else NaN.
std::vector<double> secantConcavity(const Polyline& line, double window);

// The disk concavity of every vertex: the share of the disk of `radius` around it that
// lies to the left of the line's section through the disk, minus one half, over one
// half: in [-1, 1], 0 on a straight line, positive where the line bulges to its left (the
// left side, concave there, holds more of the disk), as the secant measure. NaN where the
// section ends inside the disk.
std::vector<double> diskConcavity(const Polyline& line, double radius);

enum class Curvature { Concave, Straight, Convex };
std::string curvatureName(Curvature c);

// Runs of vertices with the same class by the secant measure (above `threshold`: convex,
// below -threshold: concave, else straight; vertices without a value join their
// neighbours' run). Each part is the line from its first to its last vertex, and parts
// share their end vertices.
struct LinePart {
  Polyline line;
  Curvature curvature;
};
std::vector<LinePart> curvatureParts(const Polyline& line, const std::vector<double>& secant, double threshold);

}  // namespace tinlod
