// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace tinlod {

using LinePoint = std::array<double, 2>;
using Polyline = std::vector<LinePoint>;

// The Douglas-Peucker simplification value of every vertex: the endpoints get infinity;
// then, within the stretch between two kept vertices a and b, the vertex farthest from
// the segment ab gets the smaller of that distance and the values of a and b, and both
// halves are treated the same way. So the simplification at any threshold t keeps
// exactly the vertices whose value exceeds t, as Douglas-Peucker with tolerance t does.
// A closed line (first vertex = last) is anchored at its start and at the vertex
// farthest from it, both infinite, so it keeps at least two sides.
// Iterative (no recursion depth limit); O(n log n) for most lines, O(n^2) at worst.
// Every vertex must be finite (readLines skips the others): distances to a NaN are NaN,
// and the line would collapse.
std::vector<double> douglasPeuckerValues(const Polyline& line);

// The line simplified at `threshold`: the vertices whose value exceeds it. O(n).
Polyline simplified(const Polyline& line, const std::vector<double>& values, double threshold);

// Pairs of segments of different lines that touch or cross (CGAL's exact test): where
// simplification brings contour lines together. A crossing through a vertex is met by
// every pair of segments there, so this counts meeting pairs, not points.
std::size_t crossingCount(const std::vector<Polyline>& lines);

}  // namespace tinlod
